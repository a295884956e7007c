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
/// below the fitted lower pole. Its height is 5–53 mm off (the depth crossing depends on the
/// breast's projection); it holds the lower pole for the shape stage only.
///
/// Once the shape is fitted the lowest breast point is placed again by proportions
/// (lowest_breast_by_proportion): on the 60 lowest breast points of the 30 benchmark and generated
/// torsos its height below the sternal notch, along the sternum, is 1.277 ± 0.018 sternum lengths
/// (notch to xiphoid; 4 mm), and 0.356 × the nipple's height below the notch + 198 mm ± 7 mm (a
/// hanging breast's fold lies lower); the fitted xiphoid is 5–15 mm off, so the two are averaged.
/// On the scan the point is the skin's front in a sagittal strip through the fitted point at that
/// height. Where the lower profile changes slope (the steep lower pole meeting the chest wall) is
/// no guide to it: that break lies 30–60 mm below the nipple on most of those torsos, where the
/// front-most skin leaves the nipple's areola, 30–50 mm above the truth on all supine ones.
#include <optional>

#include "breastfit/core/types.h"
#include "breastfit/fit/shoulder_landmarks.h"

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

/// The lowest breast point's height by proportions, and the strip it is sought in.
struct BreastFoldProportionOptions {
  double sternum_drop = 1.277;          ///< its height below the notch, in sternum lengths
  double nipple_slope = 0.356;          ///< its height below the notch per mm of the nipple's
  double nipple_offset_mm = 197.85;     ///< plus this (mm)
  double nipple_share = 0.5;            ///< the nipple's prediction's share of the height (the rest: the sternum's)
  double strip_half_width_mm = 8.0;     ///< half-width of the sagittal strip (across the body)
  double height_half_window_mm = 3.0;   ///< half-height of the slice searched at that height
  double max_in_front_of_tip_mm = 5.0;  ///< scan farther in front of the tip is not the breast (a hand, an arm)
  double max_shift_mm = 60.0;           ///< a point farther than this from the fitted one = refused
};

/// The height below the notch (mm, along the sternum) the proportions give the lowest breast point
/// of the breast whose tip lies `nipple_drop_mm` below the notch.
double lowest_breast_drop_mm(const SternumFrame& frame, double nipple_drop_mm,
                             const BreastFoldProportionOptions& options = {});

/// The lowest breast point on the scan by proportions, or nullopt when unsure: the most anterior
/// scan vertex of a sagittal strip through the fitted point's lateral position at
/// lowest_breast_drop_mm below the notch, no farther forward than the breast's tip; refused when
/// the slice holds no scan or the point lies farther than `max_shift_mm` from the fitted one.
/// \param scan_vertices the scan (mm)
/// \param tip the breast's tip (the nipple held or given)
/// \param fitted_lowest the fitted model's lowest breast point (the strip's lateral position)
/// \param frame the sternum's frame on the breast's side
std::optional<Vec3> lowest_breast_by_proportion(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                                const SternumFrame& frame,
                                                const BreastFoldProportionOptions& options = {});

}  // namespace breastfit::fit
