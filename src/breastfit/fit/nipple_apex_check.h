#pragma once
/// \file Checking a placed nipple against the breast's apex on the scan (nipple_apex.h: the most
/// forward cap along the breast's own level axis), beside the breast's tip (landmark_check.h).
///
/// On the 14 benchmark and 16 generated validation torsos as given, the nipple lies within 10 mm of
/// the level apex found around its prediction: in the sternum's frame 2.6 mm below to 8.8 mm above
/// it, within 7.3 mm sideways and within 1.7 mm in front of or behind it. A nipple walked 20 mm
/// along the skin leaves the apex behind it (it goes down the breast's slope: 2–13 mm behind) or
/// above it. On the template-made synthetic torsos, though, the template's nipple lies about 20 mm
/// *below* the level apex and up to 17 mm behind it (the template's breast points down), so
/// "behind" alone would flag them; two rules:
/// - more than `kApexAboveMm` (12 mm) above the apex: flagged (as given at most 8.8 mm; synthetic
///   at most 4.2);
/// - more than `kApexBehindMm` (5 mm) behind it, *and* not more than 6 mm below it, *and* its
///   breast's tip check at more than 0.6 of its tolerance (two signals agreeing): flagged.
#include <optional>

#include "breastfit/core/types.h"
#include "breastfit/fit/shoulder_landmarks.h"

namespace breastfit::fit {

inline constexpr double kApexAboveMm = 12.0;
inline constexpr double kApexBehindMm = 5.0;
inline constexpr double kApexBehindAllowedBelowMm = 6.0;
inline constexpr double kApexBehindTipRatio = 0.6;

/// A given nipple against the apex.
struct NippleApexCheck {
  Vec3 deviation = Vec3::Zero();  ///< given − apex in `frame`'s axes: towards the side, up, front (mm)
  double distance_mm = 0;         ///< |deviation|
  /// The rules' boundary along the deviation (mm): flagged when distance_mm > tolerance_mm; the
  /// distance itself (never flagged) when no rule applies.
  double tolerance_mm = 0;
  bool flagged() const { return distance_mm > tolerance_mm; }
};

/// The given nipple `given` against the apex `apex` found on the scan, in the sternum's frame of
/// its side; `tip_ratio` is its breast's-tip check distance over its tolerance.
NippleApexCheck check_nipple_apex(const SternumFrame& frame, const Vec3& given, const Vec3& apex, double tip_ratio);

}  // namespace breastfit::fit
