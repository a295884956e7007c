#pragma once
/// \file BreastMeasurements → JSON: the "breast_measurements" member of report.json.
#include <nlohmann/json.hpp>

#include "breastfit/transfer/breast_measurements.h"

namespace breastfit::transfer {

/// {"right": S, "left": S, "inter_nipple_mm",
///  "symmetry_left_over_right": {"volume", "notch_to_nipple", "nipple_to_imf"},
///  "chest_wall": "membrane" | "thin_plate", "chest_wall_margin_mm", "method", "warnings"},
/// S = {"volume_ml", "notch_to_nipple_mm", "nipple_to_imf_mm", "imf_lowest_mm": [x, y, z]};
/// missing values are null.
nlohmann::json to_json(const BreastMeasurements& m);

}  // namespace breastfit::transfer
