#pragma once
/// \file FitSummary as JSON (report.json's "solver").
#include <nlohmann/json_fwd.hpp>

#include "breastfit/fit/fit_summary.h"

namespace breastfit::fit {

nlohmann::json to_json(const FitSummary& s);
nlohmann::json to_json(const CorrespondenceStats& s);
/// {"total": …, "<term>": …} for every term of the breakdown.
nlohmann::json to_json(const EnergyBreakdown& e);
/// {"<landmark>": {"distance_mm", "tolerance_mm", "factor", "flagged"}, …}
nlohmann::json landmark_checks_json(const std::vector<LandmarkCheck>& checks);
/// {"<phase>": seconds, …} in order.
nlohmann::json timings_json(const std::vector<PhaseTime>& timings);

}  // namespace breastfit::fit
