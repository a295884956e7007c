#pragma once
/// \file CaseRecord ↔ JSON, and the record of a case from its report.json (pipeline::report_json).
#include <nlohmann/json.hpp>

#include "breastfit/cohort/case_record.h"

namespace breastfit::cohort {

/// The record's fields by name (nullopt → null).
nlohmann::json to_json(const CaseRecord& record);
/// The inverse of to_json. \throws InvalidInput for a missing name or status, or a wrong type
CaseRecord case_record_from_json(const nlohmann::json& j);

/// The numbers of a register report.json ("status", "time_s", "iterations", "verdict",
/// "table1", "breast_measurements", "warnings") as the record of case `name` / `scan`.
/// \throws InvalidInput when `report` is not an object with a "status" of "ok" or "not_usable"
CaseRecord case_record_from_report(const std::string& name, const std::string& scan, const nlohmann::json& report);

}  // namespace breastfit::cohort
