#include "breastfit/fit/hanging_breast_fold.h"

#include <cmath>
#include <limits>
#include <vector>

namespace breastfit::fit {

namespace {

// The front-most strip vertex's front coordinate in the slice |height − h| ≤ half, no farther
// forward than the tip allows; −inf when the slice is empty.
double front_most(const std::vector<SternumCoordinates>& strip, double h, double half) {
  double front = -std::numeric_limits<double>::infinity();
  for (const auto& p : strip)
    if (std::abs(p.height - h) <= half && p.front > front) front = p.front;
  return front;
}

// The scan vertices of the sagittal strip, in the sternum's frame, no farther forward than the tip
// allows.
std::vector<SternumCoordinates> strip_of(const Points& S, const Vec3& tip, const Vec3& fitted_lowest,
                                         const SternumFrame& frame, const HangingBreastFoldOptions& o) {
  std::vector<SternumCoordinates> out;
  const double lateral = sternum_coordinates(frame, fitted_lowest).lateral;
  const double front_limit = sternum_coordinates(frame, tip).front + o.max_in_front_of_tip_mm;
  for (Index i = 0; i < S.rows(); ++i) {
    const SternumCoordinates p = sternum_coordinates(frame, S.row(i).transpose());
    if (std::abs(p.lateral - lateral) <= o.strip_half_width_mm && p.front <= front_limit) out.push_back(p);
  }
  return out;
}

// The slice at `height_mm`: how far its front-most strip vertex lies behind the tip; nullopt when empty.
std::optional<double> behind_tip_in(const std::vector<SternumCoordinates>& strip, const Vec3& tip,
                                    const SternumFrame& frame, double height_mm, const HangingBreastFoldOptions& o) {
  const double front = front_most(strip, height_mm, o.height_half_window_mm);
  if (!std::isfinite(front)) return std::nullopt;
  return sternum_coordinates(frame, tip).front - front;
}

// hanging_breast_fold_on_scan on the strip already cut.
std::optional<Vec3> bottom_of_lower_pole_in(const std::vector<SternumCoordinates>& strip, const Vec3& fitted_lowest,
                                            const SternumFrame& frame, double height_mm,
                                            const HangingBreastFoldOptions& o) {
  if (!(o.bin_mm > 0)) return std::nullopt;
  double h = height_mm;
  double front = front_most(strip, h, o.height_half_window_mm);
  if (!std::isfinite(front)) return std::nullopt;
  for (double below = o.bin_mm; below <= o.max_below_mm + 1e-9; below += o.bin_mm) {
    const double next_h = height_mm - below;
    const double next = front_most(strip, next_h, 0.5 * o.bin_mm);
    if (!std::isfinite(next)) continue;  // an empty slice (a hole): the next one decides
    if (front - next > o.min_fall_mm) {
      const double lateral = sternum_coordinates(frame, fitted_lowest).lateral;
      const Vec3 p = frame.notch + h * frame.up + 0.5 * (front + next) * frame.front + lateral * frame.lateral;
      if (!p.allFinite()) return std::nullopt;
      return p;
    }
    h = next_h;
    front = next;
  }
  return std::nullopt;
}

}  // namespace

std::optional<double> fold_slice_behind_tip_mm(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                               const SternumFrame& frame, double height_mm,
                                               const HangingBreastFoldOptions& options) {
  if (!(frame.length_mm > 0)) return std::nullopt;
  return behind_tip_in(strip_of(scan_vertices, tip, fitted_lowest, frame, options), tip, frame, height_mm, options);
}

bool breast_hangs_over_fold(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                            const SternumFrame& frame, double height_mm, const HangingBreastFoldOptions& options) {
  const auto behind = fold_slice_behind_tip_mm(scan_vertices, tip, fitted_lowest, frame, height_mm, options);
  return behind && *behind < options.max_behind_tip_mm;
}

std::optional<Vec3> hanging_breast_fold_on_scan(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                                const SternumFrame& frame, double height_mm,
                                                const HangingBreastFoldOptions& options) {
  if (!(frame.length_mm > 0)) return std::nullopt;
  return bottom_of_lower_pole_in(strip_of(scan_vertices, tip, fitted_lowest, frame, options), fitted_lowest, frame,
                                 height_mm, options);
}

std::optional<Vec3> lowest_breast_if_hanging(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                             const SternumFrame& frame, double height_mm,
                                             const HangingBreastFoldOptions& options) {
  if (!(frame.length_mm > 0)) return std::nullopt;
  // One strip for both: whether the breast hangs, and where its lower pole ends.
  const auto strip = strip_of(scan_vertices, tip, fitted_lowest, frame, options);
  const auto behind = behind_tip_in(strip, tip, frame, height_mm, options);
  if (!behind || !(*behind < options.max_behind_tip_mm)) return std::nullopt;
  return bottom_of_lower_pole_in(strip, fitted_lowest, frame, height_mm, options);
}

}  // namespace breastfit::fit
