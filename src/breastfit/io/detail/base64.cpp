#include "breastfit/io/detail/base64.h"

namespace breastfit::io::detail {
namespace {

/// The 6-bit value of a base64 character, 64 for '=', -1 for anything else.
int sextet(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  if (c == '=') return 64;
  return -1;
}

bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }

}  // namespace

bool Base64Reader::decode_group() {
  int v[4];
  for (int k = 0; k < 4; ++k) {
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    if (pos_ >= text_.size()) return false;
    v[k] = sextet(text_[pos_++]);
    if (v[k] < 0) return false;
  }
  if (v[0] == 64 || v[1] == 64 || (v[2] == 64 && v[3] != 64)) return false;
  pending_.clear();
  pending_at_ = 0;
  pending_.push_back(static_cast<char>((v[0] << 2) | (v[1] >> 4)));
  if (v[2] != 64) pending_.push_back(static_cast<char>(((v[1] & 15) << 4) | (v[2] >> 2)));
  if (v[3] != 64) pending_.push_back(static_cast<char>(((v[2] & 3) << 6) | v[3]));
  return true;
}

bool Base64Reader::read(std::size_t count, std::string& out) {
  while (count > 0) {
    if (pending_at_ >= pending_.size() && !decode_group()) return false;
    const std::size_t take = std::min(count, pending_.size() - pending_at_);
    out.append(pending_, pending_at_, take);
    pending_at_ += take;
    count -= take;
  }
  return true;
}

}  // namespace breastfit::io::detail
