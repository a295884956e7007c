#pragma once
/// \file The acromion of a hanging arm (a subset of the landmarks given).
///
/// Arms hanging, no detector holds the acromia (the top of the shoulder in the fitted point's
/// column was tried in session 14: no gain on validation), and with the notch and the nipples given
/// the fitted template's acromion lies below and lateral of the truth by nearly the same amount on
/// every torso: in the sternum's frame (of the true notch, xiphoid and nipples), on the 14 sides of
/// the 7 standing visible benchmark torsos 4.5 mm low (SD 4.2) and 4.3 mm lateral (SD 4.6), on the
/// 16 sides of the 8 standing generated validation torsos 3.7 mm (2.8) and 3.8 mm (3.3); the front
/// is within 1 mm. The template's acromion vertex sits farther down the shoulder's lateral slope than
/// the point the benchmark's annotation takes. The target is the refined model's own point moved by
/// that offset (the visible torsos' mean; the validation torsos checked it), held at the weight of the
/// shape stage's targets.
#include "breastfit/core/types.h"
#include "breastfit/fit/shoulder_landmarks.h"

namespace breastfit::fit {

struct HangingAcromionOptions {
  double up_mm = 4.5;      ///< moved up along the sternum (towards the notch's height)
  double medial_mm = 4.3;  ///< moved towards the midline
};

/// The acromion target of a hanging arm's side: `fitted` moved `up_mm` along frame.up and
/// `medial_mm` against frame.lateral (the frame of that side: lateral points away from the midline).
Vec3 hanging_acromion_target(const Vec3& fitted, const SternumFrame& frame, const HangingAcromionOptions& options = {});

}  // namespace breastfit::fit
