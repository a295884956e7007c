#pragma once
/// \file The nipple found on the scan without its landmark: the breast's apex along the breast's own
/// forward axis, level.
///
/// The breast's tip taken along the fitted model's mean outward normal around the nipple
/// (breast_tip_on_scan, landmark_check.h) lies 5–10 mm below the nipple: the lower pole's normals,
/// facing down, tilt that mean downwards (standing and supine). With the axis made level (its
/// component along the body's vertical removed) the apex lies 2–4 mm from the true nipple on 14
/// benchmark torsos and 16 generated ones, both poses; the mean normal of the breast alone keeps
/// its lateral direction (the body's common front, from both breasts, puts it 15–20 mm too
/// medial). The apex is the centroid of the scan's cap within `cap_mm` of the most forward vertex
/// (one noisy vertex does not decide it).
///
/// Used by `breastfit landmarks` (pipeline/detect_landmarks.h) to refine the fitted nipple on the
/// scan, and landmark-free by the fit's refine stage (FitOptions::anatomical_nipple_apex): the
/// shape stage, the folds and the shoulder's targets keep the tip along the mean normal (held at
/// the apex from the shape stage on, or with the folds and shoulders placed from it, the contours
/// came out 0.15–0.6 mm worse on generated validation and hold-out torsos, docs/REGISTRATION.md).
#include <optional>

#include "breastfit/core/types.h"

namespace breastfit::fit {

/// The apex search around a fitted nipple.
struct NippleApexOptions {
  double normal_radius_mm = 40.0;  ///< model vertices this close to the fitted nipple give the breast's axis
  double search_radius_mm = 35.0;  ///< scan vertices this close to the fitted nipple are searched
  double cap_mm = 3.0;             ///< the apex: centroid of the scan vertices this close to the most forward one
};

/// The nipple on the scan near a fitted one, or nullopt when no scan vertex lies within the search
/// radius (or the model has no vertex around the nipple).
/// \param scan_vertices the scan (mm)
/// \param model_vertices, model_normals the posed model and its vertex normals (outward)
/// \param model_nipple the fitted model's nipple
/// \param up the body's superior axis (unit)
std::optional<Vec3> nipple_apex_on_scan(const Points& scan_vertices, const Points& model_vertices,
                                        const Points& model_normals, const Vec3& model_nipple, const Vec3& up,
                                        const NippleApexOptions& options = {});

}  // namespace breastfit::fit
