#pragma once
/// \file MapResult → JSON: the confidence report `breastfit map` writes next to the mapped markups.
#include <nlohmann/json.hpp>

#include "breastfit/transfer/surface_map.h"

namespace breastfit::transfer {

/// {"format": "breastfit.map", "version": 1, "units": "mm",
///  "summary": {"points", "high", "medium", "low", "mean_distance_to_fit_a_mm",
///              "max_distance_to_fit_a_mm", "supported_by_scan_b", "projected_on_scan_b"},
///  "points": [{"markup", "label", "input_mm", "output_mm", "distance_to_fit_a_mm",
///              "projected_on_scan_b", "supported_by_scan_b", "scan_b_offset_mm", "confidence"}, ...]}
/// with distances in mm.
nlohmann::json to_json(const MapResult& r);

}  // namespace breastfit::transfer
