#pragma once
/// \file SHA-256 digests of files and bytes (the provenance of a registration: which scan,
/// landmarks, template and config it read), computed by Nettle.
#include <filesystem>
#include <string>
#include <string_view>

namespace breastfit::io {

/// The SHA-256 of `bytes` as 64 lowercase hexadecimal digits.
std::string sha256_hex(std::string_view bytes);

/// The SHA-256 of a file's content as 64 lowercase hexadecimal digits (read in chunks).
/// \throws IoError(path, problem) when the file is missing, a directory or unreadable
std::string file_sha256_hex(const std::filesystem::path& path);

}  // namespace breastfit::io
