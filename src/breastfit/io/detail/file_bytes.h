#pragma once
/// \file Whole-file reads and writes with IoError messages (private to the io layer).
#include <filesystem>
#include <string>
#include <string_view>

namespace breastfit::io::detail {

/// Checks that `path` names an existing regular file (not a directory). `what` names the
/// expected kind in messages ("mesh file").
/// \throws IoError(path, problem) otherwise
void check_readable_file(const std::filesystem::path& path, std::string_view what = "mesh file");

/// Reads a whole file into memory. `what` names the expected kind in messages ("mesh file").
/// \throws IoError(path, problem) when the path is missing, a directory or unreadable
std::string read_file_bytes(const std::filesystem::path& path, std::string_view what = "mesh file");

/// Writes bytes to a file, replacing it.
/// \throws IoError(path, problem) when the file cannot be created or written
void write_file_bytes(const std::filesystem::path& path, std::string_view bytes);

}  // namespace breastfit::io::detail
