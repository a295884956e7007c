#pragma once
/// \file What a registration read and how it was run, for report.json's traceability blocks:
/// the breastfit version, each input file with its SHA-256, the effective fit options (part of
/// the deterministic `provenance` block), and the UTC start time and command line (the `run`
/// block, which differs from run to run and is the only part determinism checks skip).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "breastfit/fit/fit_options.h"

namespace breastfit::pipeline {

/// One input file: its role (scan, landmarks, template, config), path as given and SHA-256.
struct InputFile {
  std::string role;
  std::string path;
  std::string sha256;  ///< 64 lowercase hex digits
};

/// The provenance of one registration.
struct Provenance {
  std::string version;             ///< breastfit_version()
  std::vector<InputFile> inputs;   ///< in the order given
  fit::FitOptions options;         ///< the effective fit options (defaults, --config, flags)
  std::string started_utc;         ///< run block: ISO 8601 UTC start time ("2026-11-24T06:10:58Z")
  std::string command_line;        ///< run block: the command line, arguments shell-quoted

  /// The input with this role, or nullptr.
  const InputFile* input(const std::string& role) const;
};

/// "<project version> (<git describe at configure time>)", e.g. "0.1.0 (git 1a2b3c4-dirty)";
/// just the project version when the source tree was not a git checkout.
std::string breastfit_version();

/// The current time as ISO 8601 UTC with seconds ("2026-11-24T06:10:58Z").
std::string utc_now_iso8601();

/// An input file with its SHA-256. \throws IoError when the file cannot be read
InputFile hash_input(const std::string& role, const std::filesystem::path& path);

/// A provenance started now: breastfit_version(), utc_now_iso8601(), `command_line`, and each
/// (role, path) of `files` hashed in order (entries with an empty path are skipped).
/// \throws IoError when a file cannot be read
Provenance start_provenance(std::string command_line,
                            const std::vector<std::pair<std::string, std::filesystem::path>>& files);

/// The arguments joined by spaces, each quoted for a POSIX shell when it needs it.
std::string shell_command_line(const std::vector<std::string>& args);

}  // namespace breastfit::pipeline
