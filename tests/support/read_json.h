#pragma once
/// \file A JSON file the code under test wrote, parsed (throws on a missing or malformed file).
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

namespace breastfit::test {

inline nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream f(p);
  return nlohmann::json::parse(f);
}

}  // namespace breastfit::test
