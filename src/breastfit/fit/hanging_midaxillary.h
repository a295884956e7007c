#pragma once
/// \file The mid-axillary point with the arms hanging, on the scan (a subset of the landmarks
/// given).
///
/// The mid-axillary line runs down the side of the chest in the coronal plane of the shoulder
/// joint. With the arms hanging the fitted template's point lies behind it: with the notch and the
/// nipples given, 7.5 / 8.7 mm too far back (right / left, mean signed error along the body's front
/// axis) on the 7 standing benchmark torsos and 7.4 / 7.5 mm on the 8 standing generated validation
/// torsos, and 4 mm too close to the midline (the point sits on the back of the curve). Its height
/// is right on average but scatters; the truth lies 0.721 ± 0.012 sternum lengths below the notch.
/// The detector takes the scan's chest wall at that height, `front_shift_mm` in front of the
/// fitted point (the scan vertex of a thin strip there closest to the fitted point across the
/// body), and refuses a point farther than `max_shift_mm` from the fitted one (the strip can meet
/// the hanging arm instead of the chest: one of those 30 sides, 63 mm off).
#include <optional>

#include "breastfit/core/types.h"
#include "breastfit/fit/shoulder_landmarks.h"

namespace breastfit::fit {

struct HangingMidaxillaryOptions {
  double drop = 0.721;               ///< depth below the notch, in sternum lengths
  double front_shift_mm = 7.0;       ///< the strip this far in front of the fitted point
  double strip_half_width_mm = 4.0;  ///< half-width of the strip (height and antero-posterior)
  double max_shift_mm = 15.0;        ///< a point farther than this from the fitted one = refused
};

/// The mid-axillary point of a hanging arm's side on the scan, or nullopt when unsure.
/// \param scan_vertices the scan (mm), \param fitted the fitted model's mid-axillary point
std::optional<Vec3> hanging_midaxillary_on_scan(const Points& scan_vertices, const Vec3& fitted,
                                                const SternumFrame& frame,
                                                const HangingMidaxillaryOptions& options = {});

}  // namespace breastfit::fit
