#include "support/test_paths.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>
#include <sys/wait.h>

namespace breastfit::test {

std::filesystem::path data_dir() { return BREASTFIT_TEST_DATA_DIR; }
std::filesystem::path source_dir() { return BREASTFIT_SOURCE_DIR; }
std::filesystem::path cli_path() { return BREASTFIT_CLI_PATH; }

namespace {

// Every directory temp_dir() made, removed when the test process exits normally (set
// BREASTFIT_KEEP_TEST_DIRS=1 to keep them for debugging).
struct TempDirRegistry {
  std::vector<std::filesystem::path> dirs;
  ~TempDirRegistry() {
    const char* keep = std::getenv("BREASTFIT_KEEP_TEST_DIRS");
    if (keep && *keep && std::string(keep) != "0") return;
    for (const auto& d : dirs) {
      std::error_code ec;
      std::filesystem::remove_all(d, ec);
    }
  }
};

TempDirRegistry& temp_dirs() {
  static TempDirRegistry registry;
  return registry;
}

}  // namespace

std::filesystem::path temp_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "breastfit";
  for (char& c : name) {
    if (c == '/' || c == ' ') c = '_';
  }
  auto dir = std::filesystem::temp_directory_path() /
             ("breastfit_test_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  temp_dirs().dirs.push_back(dir);
  return dir;
}

int run_shell(const std::string& cmd, std::string* output) {
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buf{};
  std::string out;
  size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  if (output) *output = out;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int run_cli(const std::string& args, std::string* output) {
  return run_shell("'" + cli_path().string() + "' " + args + " 2>&1", output);
}

int run_cli_split(const std::string& args, std::string* stdout_text, std::string* stderr_text) {
  static int calls = 0;  // a file of its own per call (temp_dir() would empty the test's directory)
  const std::filesystem::path err = std::filesystem::temp_directory_path() /
                                    ("breastfit_stderr_" + std::to_string(::getpid()) + "_" + std::to_string(++calls) + ".txt");
  const int rc = run_shell("'" + cli_path().string() + "' " + args + " 2>'" + err.string() + "'", stdout_text);
  if (stderr_text) *stderr_text = file_bytes(err);
  std::error_code ec;
  std::filesystem::remove(err, ec);
  return rc;
}

std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace breastfit::test
