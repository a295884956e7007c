#pragma once
/// \file JSON text written directly, byte for byte as nlohmann::json's dump(indent) writes the
/// same values (private to the io layer): for large documents of a fixed shape (the markups'
/// control points) that are otherwise built as a DOM only to be printed once.
#include <cstddef>
#include <string>
#include <string_view>

namespace breastfit::io::detail {

/// Appends `value` as nlohmann::json writes a double: its own shortest round-trip digits
/// ("1.0", "-0.0", "1e-07"), "null" when not finite.
void append_json_number(std::string& out, double value);
/// Appends an unsigned integer as nlohmann::json writes it.
void append_json_number(std::string& out, std::size_t value);
/// Appends `text` quoted and escaped as nlohmann::json's dump() writes a string (UTF-8 kept;
/// invalid UTF-8 throws nlohmann's type_error 316 as dump() does).
void append_json_string(std::string& out, std::string_view text);

}  // namespace breastfit::io::detail
