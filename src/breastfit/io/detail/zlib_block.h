#pragma once
/// \file One zlib-compressed block (as VTK XML files store compressed arrays), inflated through
/// Debian's zlib (private to the io layer).
#include <cstddef>
#include <string>
#include <string_view>

namespace breastfit::io::detail {

/// Inflates the zlib stream `compressed`, which must decode to exactly `size` bytes, appending
/// them to `out`.
/// \return false when the stream is corrupt or its size differs from `size`
bool inflate_zlib_block(std::string_view compressed, std::size_t size, std::string& out);

}  // namespace breastfit::io::detail
