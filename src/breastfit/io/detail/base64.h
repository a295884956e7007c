#pragma once
/// \file Base64 decoding as VTK XML files use it (private to the io layer): the text may be
/// several padded base64 strings one after the other (VTK encodes a compressed array's header
/// and its data separately), and may hold whitespace.
#include <cstddef>
#include <string>
#include <string_view>

namespace breastfit::io::detail {

/// Decodes base64 text on demand, from a start position, group of 4 characters by group.
class Base64Reader {
 public:
  /// \param text  the encoded characters (decoding starts at text[0])
  explicit Base64Reader(std::string_view text) : text_(text) {}

  /// Appends the next `count` decoded bytes to `out`.
  /// \return false when the text ends (or holds a character outside base64) before `count`
  ///         bytes; `out` then holds what could be decoded
  bool read(std::size_t count, std::string& out);

 private:
  bool decode_group();  // decodes the next 4 characters into pending_

  std::string_view text_;
  std::size_t pos_ = 0;
  std::string pending_;
  std::size_t pending_at_ = 0;
};

}  // namespace breastfit::io::detail
