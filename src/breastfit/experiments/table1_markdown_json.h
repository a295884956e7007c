#pragma once
/// \file Table 1 of the paper as Markdown, from the JSON of run_experiments: standing and supine
/// separately, one row per case and a mean row, next to the paper's mean row; the paper's way
/// (model → scan) and against the truth; and, when the JSON holds the external referee's
/// numbers ("referee", added by `breastfit experiments --referee`), the referee's table.
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace breastfit::experiments {

/// The paper's Table 1 mean rows (Mazier et al. 2022): time s, surface MAE/SD/max, landmark
/// MAE/SD/max/min (mm), for "standing" (preoperative) and "supine" (intra-operative).
struct PaperTable1Mean {
  double time_s, surface_mae, surface_sd, surface_max, landmark_mae, landmark_sd, landmark_max, landmark_min;
};
PaperTable1Mean paper_table1_mean(const std::string& pose);

/// The Markdown text (empty tables when the JSON has no "table1").
std::string table1_markdown(const nlohmann::json& experiments);

}  // namespace breastfit::experiments
