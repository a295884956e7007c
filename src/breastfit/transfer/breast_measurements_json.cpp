#include "breastfit/transfer/breast_measurements_json.h"

namespace breastfit::transfer {
namespace {

nlohmann::json opt(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

nlohmann::json side(const BreastSide& b) {
  nlohmann::json j = {{"volume_ml", opt(b.volume_ml)},
                      {"notch_to_nipple_mm", opt(b.notch_to_nipple_mm)},
                      {"nipple_to_imf_mm", opt(b.nipple_to_imf_mm)}};
  j["imf_lowest_mm"] = b.imf_lowest_mm ? nlohmann::json{b.imf_lowest_mm->x(), b.imf_lowest_mm->y(), b.imf_lowest_mm->z()}
                                       : nlohmann::json(nullptr);
  return j;
}

}  // namespace

nlohmann::json to_json(const BreastMeasurements& m) {
  return {{"right", side(m.right)},
          {"left", side(m.left)},
          {"inter_nipple_mm", opt(m.inter_nipple_mm)},
          {"symmetry_left_over_right",
           {{"volume", opt(m.volume_ratio)},
            {"notch_to_nipple", opt(m.notch_to_nipple_ratio)},
            {"nipple_to_imf", opt(m.nipple_to_imf_ratio)}}},
          {"chest_wall", m.volume_options.fill == ChestWallFill::ThinPlate ? "thin_plate" : "membrane"},
          {"chest_wall_margin_mm", m.volume_options.margin_mm},
          {"method",
           "volume between the fitted skin inside the breast contour (breast_contour_R/L on the fitted model) and a "
           "chest-wall fill spanning the contour (harmonic membrane, or thin plate); straight-line distances on the fitted "
           "model; lowest fold point along xiphoid->sternal_notch"},
          {"warnings", m.warnings}};
}

}  // namespace breastfit::transfer
