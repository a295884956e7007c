#include "breastfit/io/detail/file_bytes.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "breastfit/core/errors.h"

namespace breastfit::io::detail {

void check_readable_file(const std::filesystem::path& path, std::string_view what) {
  const std::string name = path.string();
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    throw IoError(name, "file does not exist");
  }
  if (std::filesystem::is_directory(status)) {
    throw IoError(name, "is a directory, not a " + std::string(what));
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw IoError(name, "is not a regular file");
  }
}

std::string read_file_bytes(const std::filesystem::path& path, std::string_view what) {
  const std::string name = path.string();
  check_readable_file(path, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw IoError(name, std::string("cannot open for reading (") + std::strerror(errno) + ")");
  }
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) {
    throw IoError(name, "cannot determine the file size");
  }
  in.seekg(0, std::ios::beg);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (size > 0 && !in.read(bytes.data(), size)) {
    throw IoError(name, "read failed before the end of the file");
  }
  return bytes;
}

void write_file_bytes(const std::filesystem::path& path, std::string_view bytes) {
  const std::string name = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw IoError(name, "is a directory, cannot write a mesh file there");
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) {
    throw IoError(name, std::string("cannot open for writing (") + std::strerror(errno) + ")");
  }
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    throw IoError(name, "write failed (disk full?)");
  }
}

}  // namespace breastfit::io::detail
