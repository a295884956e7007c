#pragma once
/// \file The sternum's length from the sternal notch and the nipples (a subset of the landmarks
/// given).
///
/// With only the notch and the nipples given, the fitted xiphoid ends 5 mm from the truth on average
/// (the sternum's length −9 … +15 mm off on the 14 benchmark torsos, 4–5 mm mean absolute on them
/// and on the 16 generated validation torsos), and every proportion taken from it — the shoulder's
/// landmarks (shoulder_landmarks.h), the lowest breast points (breast_fold.h) — carries that error
/// 0.7–1.3 times. The given landmarks themselves say more: the mean distance from the notch to the
/// two nipples (d) predicts the length as 0.314 d + 136.5 mm, residual 3.2 mm (standard deviation)
/// on the given landmarks of those 30 torsos, standing and supine pooled (per pose 3.2 and 2.9 mm:
/// not worth knowing the pose); fitted on the 14 benchmark torsos alone it predicts the 16 others
/// to 3.2 mm (mean absolute). A breast's tip moves with the body's size; its droop adds to d, which
/// is why the slope is well under 1.
///
/// The xiphoid is then put at that length along the fitted sternum (notch → fitted xiphoid): the
/// direction the fit gives, the length the proportions give.
#include <optional>

#include "breastfit/core/types.h"

namespace breastfit::fit {

struct SternumLengthOptions {
  double slope = 0.314;      ///< sternum length per mm of the mean notch-to-nipple distance
  double offset_mm = 136.5;  ///< plus this (mm)
  /// A xiphoid placed farther than this from the fitted one = refused (the fit and the proportion
  /// disagree too much for either to be trusted; 15 mm at most on the 30 torsos).
  double max_shift_mm = 30.0;
};

/// The sternum's length (mm, notch to xiphoid) the notch and the nipples predict.
double sternum_length_by_nipples_mm(const Vec3& notch, const Vec3& nipple_R, const Vec3& nipple_L,
                                    const SternumLengthOptions& options = {});

/// The xiphoid at sternum_length_by_nipples_mm from the notch along the fitted sternum, or nullopt
/// when the fitted sternum is degenerate or the point lies farther than `max_shift_mm` from the
/// fitted xiphoid.
std::optional<Vec3> xiphoid_by_nipples(const Vec3& notch, const Vec3& nipple_R, const Vec3& nipple_L,
                                       const Vec3& fitted_xiphoid, const SternumLengthOptions& options = {});

}  // namespace breastfit::fit
