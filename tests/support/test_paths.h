#pragma once
// Paths the tests need: the repository's test data, the source tree and the built CLI.
#include <filesystem>
#include <string>

namespace breastfit::test {

/// tests/data in the source tree (small hand-written fixtures only).
std::filesystem::path data_dir();
/// The repository root.
std::filesystem::path source_dir();
/// The built `breastfit` executable (empty when the CLI is not built).
std::filesystem::path cli_path();
/// A fresh, empty temporary directory unique to the calling test (removed when the test process
/// exits normally; BREASTFIT_KEEP_TEST_DIRS=1 keeps it).
std::filesystem::path temp_dir();

/// The bytes of a file ("" when it cannot be read).
std::string file_bytes(const std::filesystem::path& path);

/// Runs `cmd` through /bin/sh, captures its stdout into `output`; returns the exit code.
int run_shell(const std::string& cmd, std::string* output = nullptr);

/// Runs the CLI with the given argument string through /bin/sh; returns the exit code and
/// captures stdout+stderr into `output`.
int run_cli(const std::string& args, std::string* output = nullptr);

/// run_cli with stdout and stderr apart (e.g. `--json` output that a warning must not break).
int run_cli_split(const std::string& args, std::string* stdout_text, std::string* stderr_text = nullptr);

}  // namespace breastfit::test
