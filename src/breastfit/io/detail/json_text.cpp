#include "breastfit/io/detail/json_text.h"

#include <array>
#include <cmath>

#include <nlohmann/json.hpp>

namespace breastfit::io::detail {

void append_json_number(std::string& out, double value) {
  if (!std::isfinite(value)) {
    out += "null";
    return;
  }
  // The routine nlohmann::json's serializer itself calls for a double (Grisu2, then its own
  // layout): the same text as dump(), which std::to_chars (Ryu, another layout) would not give.
  std::array<char, 64> buffer{};
  const char* end = nlohmann::detail::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  out.append(buffer.data(), static_cast<std::size_t>(end - buffer.data()));
}

void append_json_number(std::string& out, std::size_t value) { out += std::to_string(value); }

void append_json_string(std::string& out, std::string_view text) {
  // Names are short and few (one per markup and point): the library's own escaping, exactly.
  out += nlohmann::json(std::string(text)).dump();
}

}  // namespace breastfit::io::detail
