#pragma once
/// \file Checking a placed xiphoid against the lowest breast points' height: the sternum's
/// proportions.
///
/// The lowest breast points lie 1.277 ± 0.018 sternum lengths (notch to xiphoid) below the notch
/// (breast_fold.h). Turned round, the given lowest breast points and notch say how long the sternum
/// is: a xiphoid walked down the abdomen makes it too long. The residual is the sternum's length
/// as given (notch → xiphoid along the fitted sternum's axis) minus the mean depth of the two
/// lowest breast points below the notch divided by 1.277. As given it lies between −11.1 and
/// +7.0 mm on the 14 benchmark and 16 generated validation torsos (the given landmarks scatter
/// more than the truth), +12.7 mm at most on the template-made synthetic ones; a xiphoid more than
/// `kXiphoidTooLowMm` (13 mm) too low is flagged. Only that side: too short a sternum is as often a
/// lowest breast point placed low.
#include <optional>

#include "breastfit/core/types.h"

namespace breastfit::fit {

inline constexpr double kXiphoidTooLowMm = 13.0;
inline constexpr double kLowestBreastSternumLengths = 1.277;

/// The sternum's length as given minus the one the lowest breast points' depth gives (mm; > 0: the
/// xiphoid lies too low). \param up the fitted sternum's axis (unit, towards the head)
double xiphoid_residual_mm(const Vec3& notch, const Vec3& xiphoid, const Vec3& lowest_breast_R,
                           const Vec3& lowest_breast_L, const Vec3& up);

}  // namespace breastfit::fit
