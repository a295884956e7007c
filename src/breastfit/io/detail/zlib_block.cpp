#include "breastfit/io/detail/zlib_block.h"

#include <zlib.h>

#include <limits>

namespace breastfit::io::detail {

bool inflate_zlib_block(std::string_view compressed, std::size_t size, std::string& out) {
  if (compressed.size() > std::numeric_limits<uLong>::max() ||
      size > std::numeric_limits<uLong>::max()) {
    return false;
  }
  const std::size_t at = out.size();
  out.resize(at + size);
  uLongf length = static_cast<uLongf>(size);
  const int status =
      uncompress(reinterpret_cast<Bytef*>(out.data() + at), &length,
                 reinterpret_cast<const Bytef*>(compressed.data()), static_cast<uLong>(compressed.size()));
  if (status != Z_OK || length != size) {
    out.resize(at);
    return false;
  }
  return true;
}

}  // namespace breastfit::io::detail
