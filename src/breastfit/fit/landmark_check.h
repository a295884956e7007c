#pragma once
/// \file Checking the landmarks a person placed against the fitted anatomy, and the robust weight
/// that keeps one bad click from dragging the fit.
///
/// A landmark's *check distance* is the distance between the landmark given on the scan and the
/// fitted model's landmark (the sliding definition for the lowest breast points). On the 14
/// benchmark cases with their landmarks as given, it stays ≤ 4.2 mm for the material and sliding
/// landmarks and ≤ 22 mm for the mid-axillary points (line landmarks on skin that slides with the
/// arm, weighted 0.1). Beyond a tolerance — FitOptions::landmark_check_mm (15 mm), twice that for
/// the mid-axillary points — a landmark is flagged, and during the stages with
/// StageOptions::robust_landmarks its weight is multiplied by (tolerance / distance)², held fixed
/// while each step is solved (IRLS): its pull on the fit fades instead of growing with the error.
///
/// The fit follows a wrong click (the template slides), so each landmark is also compared with its
/// *prediction* — where the scan's anatomy and the other landmarks put it (landmark_prediction.h)
/// — with a per-landmark tolerance (placed_landmark_tolerance_mm); one beyond it is flagged, its
/// weight multiplied by (tolerance / distance)² and the refine stage run again without its pull.
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/fit/landmark_target.h"

namespace breastfit::fit {

/// The check tolerance of a landmark (mm): `landmark_check_mm`, ×2 for the mid-axillary points.
double landmark_check_tolerance_mm(const std::string& name, double landmark_check_mm);

/// Landmarks needed before each given landmark is checked against its prediction
/// (landmark_prediction.h): with fewer, the others say too little about where it belongs.
inline constexpr size_t kMinLandmarksToPredict = 3;

/// The tolerance of a landmark's prediction check (mm): given landmark ↔ where the scan's
/// anatomy and the other landmarks put it.
double placed_landmark_tolerance_mm(const std::string& name, double landmark_check_mm);

/// Whether a re-linearised leave-one-out prediction (landmark_prediction.h) of the landmark is as
/// sharp as its tolerance: the sternal notch, xiphoid, acromia and pectoral insertions. Without a
/// lowest breast point, a nipple or a mid-axillary point the model's breast and side slide as far
/// as in a landmark-free fit (a lowest breast point as given on a benchmark torso: 13–17 mm linear,
/// 20–26 mm re-linearised).
bool relinearized_prediction_is_sharp(const std::string& name);

/// IRLS factor of a landmark at check distance `distance_mm`: 1 within the tolerance,
/// (tolerance / distance)² beyond.
double robust_landmark_factor(double distance_mm, double tolerance_mm);

/// One given landmark after the fit.
struct LandmarkCheck {
  std::string name;
  double distance_mm = 0;   ///< given landmark ↔ fitted model landmark
  double tolerance_mm = 0;
  double factor = 1;        ///< robust factor the fit's last stage gave it (1 = full weight)
  /// Given landmark ↔ the landmark found on the scan by its own anatomical definition — the
  /// nipples: the breast's tip (breast_tip_on_scan), apex (nipple_apex_check.h) or the nipple's
  /// own bump (nipple_bump_check.h, where the scan shows a distinct one); the sternal
  /// notch: the jugular notch on the other landmarks' midline (midline_notch_check.h); the pairs'
  /// mirror image (bilateral_check.h); the insertions' arm (pectoral_check.h); the xiphoid: the
  /// lowest breast points' height (xiphoid_check.h); any of them with the prediction agreeing
  /// (combined_check.h) — the one farthest beyond its tolerance; < 0 when not checked.
  double anatomy_distance_mm = -1;
  double anatomy_tolerance_mm = 0;
  std::string anatomy;      ///< what was found on the scan ("the breast's tip", …); empty when not checked
  /// Given landmark ↔ where the scan's anatomy and the other landmarks put it
  /// (landmark_prediction.h); < 0 when not checked.
  double predicted_distance_mm = -1;
  double predicted_tolerance_mm = 0;
  bool flagged = false;     ///< beyond a tolerance: check this landmark
};

/// Pairs of given landmarks whose labels look exchanged: both beyond their prediction check, and
/// each within its tolerance of where the other one belongs. `predicted[i]` is the prediction of
/// `given[i]` (landmark_prediction.h). Indices into `given`, the smaller first.
std::vector<std::pair<size_t, size_t>> exchanged_labels(const std::vector<LandmarkTarget>& given,
                                                        const std::vector<Vec3>& predicted,
                                                        double landmark_check_mm);

/// The breast's tip on the scan near a nipple: among the scan's vertices within
/// `search_radius_mm` of `model_nipple`, the one farthest along the mean outward normal of the
/// surface (`model_vertices`, `model_normals`) within 40 mm of it. The fit can follow a wrongly
/// placed nipple by sliding the breast's skin (the surface barely changes), so the nipple is
/// checked against the scan's own geometry — with the scan as the surface too (the fitted model's
/// normals turn with the click); landmark-free, the fitted model's normals place the nipple.
/// nullopt when no scan vertex is that close.
std::optional<Vec3> breast_tip_on_scan(const Points& scan_vertices, const Points& model_vertices,
                                       const Points& model_normals, const Vec3& model_nipple,
                                       double search_radius_mm = 35.0);

}  // namespace breastfit::fit
