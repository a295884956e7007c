#pragma once
/// \file The lowest breast point found on the scan without its landmark: where the breast's lower
/// pole meets the chest wall at the fold.
///
/// Without a placed lowest breast point the fit leaves the breast's lower pole about 35 mm too
/// high (the scanner sees the hanging lower pole poorly and the surface hides the difference). On
/// the scan, below the breast's tip, the most anterior skin at each height recedes towards the
/// chest wall as one goes down the breast's lower pole; the fold — the lowest point of the breast
/// mound — lies on the chest wall a nearly constant depth behind the tip (45–75 mm, mean 55 mm on
/// 30 generated standing and supine torsos of all breast sizes). The detector follows the scan's
/// profile in a sagittal strip through the fitted lowest point, from the tip downwards, and
/// returns the first point that lies that far behind the tip. It refuses (nullopt) when the
/// strip has too little scan (holes), the profile does not cross that depth, or crosses it far
/// below the fitted lower pole.
#include <optional>

#include "breastfit/core/types.h"

namespace breastfit::fit {

/// The fold's depth behind the breast's tip (mm) and the profile's sampling.
struct BreastFoldOptions {
  double depth_behind_tip_mm = 55.0;  ///< the fold's depth behind the tip along the body's front axis
  double strip_half_width_mm = 8.0;   ///< half-width of the sagittal strip
  double bin_mm = 3.0;                ///< height bins of the profile
  double min_drop_mm = 10.0;          ///< the search starts this far below the tip
  double max_drop_mm = 140.0;         ///< and ends this far below it
  double max_gap_mm = 15.0;           ///< a longer run of empty bins before the crossing = refused
  /// A crossing farther than this below the fitted lowest point is refused: the breast is shallower
  /// than the fold's depth assumes and the profile crossed it on the abdomen (with the notch and
  /// nipples given, the folds found on the 14 visible benchmark torsos lay at most 48 mm below the
  /// fitted point; on a template-made supine torso, 58 mm below, 35 mm too low).
  double max_below_fitted_mm = 50.0;
};

/// The lowest breast point on the scan, or nullopt when unsure.
/// \param scan_vertices the scan (mm)
/// \param tip the breast's tip (the nipple) on the scan
/// \param fitted_lowest the fitted model's lowest breast point (gives the strip's lateral position
///        and bounds the crossing's height)
/// \param up the body's superior axis, \param front its anterior axis (unit, orthogonal)
std::optional<Vec3> lowest_breast_on_scan(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                          const Vec3& up, const Vec3& front, const BreastFoldOptions& options = {});

}  // namespace breastfit::fit
