#pragma once
/// \file The sternal (jugular) notch found on the scan without its landmark: where the front of
/// the manubrium meets the neck.
///
/// Without a placed notch the fit leaves it 8–12 mm too low (the surface of the upper sternum and
/// the neck is smooth: nothing holds the template's notch in place along it). On the scan, along
/// the body's midline, the skin in front of the sternum recedes going up (the manubrium slopes back)
/// until the notch, and above it the neck's front rises nearly vertically. The detector takes the
/// midline profile — the most anterior scan point in each height bin of a thin sagittal strip
/// through the fitted notch — and fits two straight lines to it, one below and one above a break
/// height; the break that fits best, when the profile is clearly steeper below than above, is the
/// notch, placed on the fitted midline (the strip's front-most vertex may lie a few mm to one
/// side, which dragged the fitted sternum sideways). It refuses (nullopt) when the strip has too
/// little scan or the profile has no such break.
#include <optional>

#include "breastfit/core/types.h"

namespace breastfit::fit {

/// The profile's window around the fitted notch and the break it must show.
struct JugularNotchOptions {
  double strip_half_width_mm = 5.0;  ///< half-width of the sagittal strip
  double bin_mm = 3.0;               ///< height bins of the profile
  double below_mm = 40.0;            ///< the profile starts this far below the fitted notch
  double above_mm = 45.0;            ///< and ends this far above it (or at the first hole: the neck's cut)
  double max_gap_mm = 6.0;           ///< a longer run of empty bins ends the profile
  /// Scan farther than this behind the fitted notch is ignored (the back of the neck, seen through
  /// the neck's cut).
  double max_behind_mm = 30.0;
  int min_bins_each_side = 4;        ///< the break needs this many profile points below and above it
  /// The profile must recede at least this much faster below the break than above it
  /// (mm of depth per mm of height).
  double min_slope_change = 0.15;
};

/// The notch on the scan (in the fitted notch's sagittal plane), or nullopt when unsure.
/// \param scan_vertices the scan (mm)
/// \param fitted_notch the fitted model's notch (the strip's position and the window's centre)
/// \param up the body's superior axis, \param front its anterior axis (unit, orthogonal)
std::optional<Vec3> jugular_notch_on_scan(const Points& scan_vertices, const Vec3& fitted_notch, const Vec3& up,
                                          const Vec3& front, const JugularNotchOptions& options = {});

}  // namespace breastfit::fit
