#pragma once
/// \file Number parsing/formatting and message helpers shared by the mesh readers/writers
/// (private to the io layer). All functions are allocation-free except the string formatters.
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>

namespace breastfit::io::detail {

/// True for the blank characters that separate tokens in text mesh formats.
inline bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

/// Parses a whole token as a double ("1", "-2.5e3", "+4", "nan", "inf"); false if any character
/// is left over or the token is empty / out of range.
inline bool parse_double(std::string_view token, double& out) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, out);
  return result.ec == std::errc() && result.ptr == end;
}

/// Parses a whole token as a signed 64-bit integer ("12", "-3", "+4").
inline bool parse_int64(std::string_view token, std::int64_t& out) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, out);
  return result.ec == std::errc() && result.ptr == end;
}

/// Splits off the next whitespace-separated token of `line` (advancing it); empty at the end.
inline std::string_view next_token(std::string_view& line) {
  std::size_t i = 0;
  while (i < line.size() && is_blank(line[i])) ++i;
  std::size_t j = i;
  while (j < line.size() && !is_blank(line[j])) ++j;
  const std::string_view token = line.substr(i, j - i);
  line.remove_prefix(j);
  return token;
}

/// A token quoted for an error message: at most 32 characters, non-printable bytes as '?'.
std::string quoted(std::string_view token);

/// The shortest decimal text that parses back to exactly `value`.
std::string format_double(double value);
/// The shortest decimal text that parses back (as float) to exactly `value`.
std::string format_float(float value);

/// Replaces bare NaN / Infinity / -Infinity tokens outside JSON strings (as Python's json module
/// writes them) by the strings "NaN", "Infinity", "-Infinity", so that the document parses and
/// the coordinate check can name the point that holds them.
std::string quote_non_finite_tokens(std::string_view text);

}  // namespace breastfit::io::detail
