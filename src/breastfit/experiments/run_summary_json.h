#pragma once
/// \file Means of a set of runs (one configuration over the cases), standing and supine
/// separately and together: the "Mean" rows of Table 1 and the points of Figs 4–8.
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "breastfit/experiments/run_record.h"

namespace breastfit::experiments {

/// {"standing": G, "supine": G, "all": G} (a pose group only when it has runs), each
/// G = {"n", "n_not_converged", "n_not_usable", "n_error", "time_s", "iterations",
///      "paper": {"surface": {"mae","sd","max"}, "landmarks": {"mae","sd","max","min"}},
///      "truth": {"n", "surface": {...}, "landmarks": {...}, "drawings_mm": {name: mean}}}:
/// means over the runs that produced numbers (status ok, not_usable or not_converged; truth over those
/// with truth). A mean over no run is null.
nlohmann::json summarize(const std::vector<const RunRecord*>& runs);

}  // namespace breastfit::experiments
