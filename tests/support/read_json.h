#pragma once
/// \file JSON the code under test wrote, parsed: a file (throws on a missing or malformed file),
/// or what a CLI run printed on stdout (`--json`).
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_paths.h"

namespace breastfit::test {

inline nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream f(p);
  return nlohmann::json::parse(f);
}

/// The JSON a CLI run prints on stdout (its stderr apart, so a warning does not break it);
/// a failure of the test when it does not exit 0 or prints no JSON (then null).
inline nlohmann::json run_cli_json(const std::string& args) {
  std::string out, err;
  EXPECT_EQ(run_cli_split(args, &out, &err), 0) << args << "\n" << out << err;
  try {
    return nlohmann::json::parse(out);
  } catch (const nlohmann::json::parse_error& e) {
    ADD_FAILURE() << "not JSON: " << e.what() << "\n" << out << err;
    return nlohmann::json();
  }
}

}  // namespace breastfit::test
