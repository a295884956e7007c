#pragma once
/// \file The lowest breast point under a hanging breast (a subset of the landmarks given).
///
/// With the notch and the nipples given, the lowest breast point is placed by proportions
/// (lowest_breast_by_proportion, breast_fold.h): the front-most skin of a sagittal strip at the
/// fold's predicted height. On a breast that hangs over its fold that slice still meets the
/// breast's front: on the benchmark's and the generated validation torsos the front-most skin there
/// lay 2–16 mm behind the breast's tip on the four hanging sides (two torsos, standing), ≥ 40 mm
/// behind it on the other 56 sides and ≥ 30 mm on 26 template-made ones (the fold itself 45–75 mm),
/// and those four targets were 37–57 mm from the truth. The truth lies at the bottom of the lower pole,
/// where the breast meets the chest wall: going down the strip from that height, the front-most
/// skin falls back by 42–66 mm from one 3 mm slice to the next (the breast's underside, unseen by
/// the scanner, to the chest wall below it). The point returned lies at the last slice with breast,
/// halfway between the breast's front there and the chest wall below (the crease is under the
/// breast, between the two): 7.6–11 mm from the truth on those four sides.
#include <optional>

#include "breastfit/core/types.h"
#include "breastfit/fit/shoulder_landmarks.h"

namespace breastfit::fit {

struct HangingBreastFoldOptions {
  /// The breast hangs over its fold when the front-most skin at the fold's height lies less than
  /// this behind the tip. On 70 benchmark and generated torsos (140 sides, 3 landmarks given and
  /// none): 4.5–26.5 mm on the 7 sides that hang, ≥ 29 mm on all the others (supine breasts
  /// without landmarks 29–33, with 3 landmarks ≥ 33.5); 28 lies between. It was 23 (between the
  /// 2–16 mm of the first four hanging sides and ≥ 30) until three hanging sides of generated
  /// torsos at 23.5–26.5 mm took the proportion's point on the breast's front, 29–65 mm off.
  double max_behind_tip_mm = 28.0;
  double strip_half_width_mm = 8.0;    ///< half-width of the sagittal strip (across the body)
  double height_half_window_mm = 3.0;  ///< half-height of the slice at the fold's height
  double max_in_front_of_tip_mm = 5.0; ///< scan farther in front of the tip is not the breast
  double bin_mm = 3.0;                 ///< slices below that height
  /// The breast's bottom: the front-most skin falls back by more than this from one slice to the
  /// next (42–66 mm on the hanging sides).
  double min_fall_mm = 20.0;
  double max_below_mm = 60.0;          ///< the bottom sought this far below the fold's height, else refused
};

/// How far behind the tip (mm, along the sternum frame's front) the front-most scan vertex of the
/// sagittal strip through `fitted_lowest`'s lateral position lies at `height_mm` (along the sternum
/// from the notch, negative below it); nullopt when the slice holds no scan.
std::optional<double> fold_slice_behind_tip_mm(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                               const SternumFrame& frame, double height_mm,
                                               const HangingBreastFoldOptions& options = {});

/// Whether the breast hangs over the fold's predicted height: the slice there
/// (fold_slice_behind_tip_mm) lies less than `max_behind_tip_mm` behind the tip. False when the
/// slice holds no scan.
bool breast_hangs_over_fold(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                            const SternumFrame& frame, double height_mm, const HangingBreastFoldOptions& options = {});

/// The lowest breast point under a hanging breast: from `height_mm` down the strip, the last slice
/// before the front-most skin falls back by more than `min_fall_mm`; the point at that slice's
/// height, halfway between the two fronts, in the strip's middle. nullopt when the fall is not
/// found within `max_below_mm` (or the frame is degenerate).
std::optional<Vec3> hanging_breast_fold_on_scan(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                                const SternumFrame& frame, double height_mm,
                                                const HangingBreastFoldOptions& options = {});

/// The lowest breast point where the breast hangs over the fold's height (breast_hangs_over_fold):
/// the bottom of its lower pole (hanging_breast_fold_on_scan). nullopt when the slice there lies
/// behind on the chest wall, holds no scan, or no fall is found below it: the caller places the
/// point by proportions then.
std::optional<Vec3> lowest_breast_if_hanging(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                             const SternumFrame& frame, double height_mm,
                                             const HangingBreastFoldOptions& options = {});

}  // namespace breastfit::fit
