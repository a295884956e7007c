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
/// The landmark-free initialisation's choice: {"chosen", "runner_up", "margin" (null = no
/// runner-up), "confident", "body_frame", "arm_abduction_deg", "arm_pose", "candidates"}; null when
/// initialised from landmarks.
nlohmann::json orientation_json(const OrientationSummary& o);
/// {"<phase>": seconds, …}; a phase listed more than once (the refine stage run again after a
/// flagged landmark) is the sum of its runs.
nlohmann::json timings_json(const std::vector<PhaseTime>& timings);

}  // namespace breastfit::fit
