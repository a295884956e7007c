#pragma once
/// \file Checking a placed nipple against the nipple's own bump on the scan (nipple_bump.h).
///
/// The bump is searched around where the other landmarks put the nipple (its prediction,
/// landmark_prediction.h), not around the given or the fitted nipple: the fit follows a wrong
/// click. A given nipple farther than `kNippleBumpCheckMm` (scaled with landmark_check_mm / 15)
/// from the bump is flagged. Where the scan shows no distinct bump (nipple_bump_on_scan refuses:
/// the template-made synthetic torsos, a scan artefact) nothing is checked this way and the
/// breast's tip and apex checks stand alone. Measured in docs/REGISTRATION.md, session 15.
#include "breastfit/core/types.h"
#include "breastfit/fit/nipple_bump.h"

namespace breastfit::fit {

inline constexpr double kNippleBumpCheckMm = 12.0;

/// A given nipple against the bump found on the scan.
struct NippleBumpCheck {
  double distance_mm = 0;   ///< given nipple ↔ bump
  double tolerance_mm = 0;
  bool flagged() const { return distance_mm > tolerance_mm; }
};

NippleBumpCheck check_nipple_bump(const Vec3& given, const NippleBump& bump, double landmark_check_mm);

}  // namespace breastfit::fit
