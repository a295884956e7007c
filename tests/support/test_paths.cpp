#include "support/test_paths.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>

namespace breastfit::test {

std::filesystem::path data_dir() { return BREASTFIT_TEST_DATA_DIR; }
std::filesystem::path source_dir() { return BREASTFIT_SOURCE_DIR; }
std::filesystem::path cli_path() { return BREASTFIT_CLI_PATH; }

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
  return dir;
}

int run_cli(const std::string& args, std::string* output) {
  const std::string cmd = "'" + cli_path().string() + "' " + args + " 2>&1";
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

}  // namespace breastfit::test
