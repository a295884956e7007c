#include "breastfit/io/file_sha256.h"

#include <nettle/sha2.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <system_error>

#include "breastfit/core/errors.h"

namespace breastfit::io {
namespace {

/// A SHA-256 computation (Nettle's: a small library with nothing to initialise when a program
/// starts, unlike OpenSSL's libcrypto, whose loading alone cost every run ~6 ms of CPU).
class Sha256 {
 public:
  Sha256() { sha256_init(&ctx_); }
  void update(const char* data, std::size_t size) {
    sha256_update(&ctx_, size, reinterpret_cast<const std::uint8_t*>(data));
  }
  std::string hex() {
    std::array<std::uint8_t, SHA256_DIGEST_SIZE> digest{};
    sha256_digest(&ctx_, digest.size(), digest.data());
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    for (const std::uint8_t b : digest) {
      out.push_back(kHex[b >> 4]);
      out.push_back(kHex[b & 15]);
    }
    return out;
  }

 private:
  sha256_ctx ctx_{};
};

}  // namespace

std::string sha256_hex(std::string_view bytes) {
  Sha256 h;
  h.update(bytes.data(), bytes.size());
  return h.hex();
}

std::string file_sha256_hex(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(path.string(), "file does not exist");
  if (std::filesystem::is_directory(path, ec)) throw IoError(path.string(), "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string(), "cannot open for reading");
  Sha256 h;
  std::array<char, 1 << 16> buffer{};
  while (in) {
    in.read(buffer.data(), buffer.size());
    h.update(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw IoError(path.string(), "read failed");
  return h.hex();
}

}  // namespace breastfit::io
