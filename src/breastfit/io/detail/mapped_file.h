#pragma once
/// \file A file's bytes mapped read-only into memory (private to the io layer): large scans are
/// parsed where the page cache holds them, without zero-filling and copying a buffer first.
#include <cstddef>
#include <filesystem>
#include <string_view>

namespace breastfit::io::detail {

class MappedFile {
 public:
  /// Maps the whole file. `what` names the expected kind in messages ("mesh file").
  /// \throws IoError(path, problem) when the path is missing, a directory or unreadable (the
  /// messages of read_file_bytes)
  explicit MappedFile(const std::filesystem::path& path, std::string_view what = "mesh file");
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  /// The file's bytes (empty for an empty file), valid while this object lives.
  std::string_view bytes() const { return {static_cast<const char*>(data_), size_}; }

 private:
  void* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace breastfit::io::detail
