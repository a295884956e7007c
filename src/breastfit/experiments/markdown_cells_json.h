#pragma once
/// \file Small helpers shared by the Markdown writers of the experiments: reading a number at a
/// path of experiments.json and formatting it as a table cell.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace breastfit::experiments {

/// j at the path of object keys, or a null value when any key is missing.
const nlohmann::json& json_at(const nlohmann::json& j, const std::vector<const char*>& path);

/// A number with `digits` decimals, or "–" when v is not a number.
std::string cell(const nlohmann::json& v, int digits = 2);

}  // namespace breastfit::experiments
