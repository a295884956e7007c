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

}  // namespace

std::optional<double> fold_slice_behind_tip_mm(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                               const SternumFrame& frame, double height_mm,
                                               const HangingBreastFoldOptions& options) {
  if (!(frame.length_mm > 0)) return std::nullopt;
  const auto strip = strip_of(scan_vertices, tip, fitted_lowest, frame, options);
  const double front = front_most(strip, height_mm, options.height_half_window_mm);
  if (!std::isfinite(front)) return std::nullopt;
  return sternum_coordinates(frame, tip).front - front;
}

bool breast_hangs_over_fold(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                            const SternumFrame& frame, double height_mm, const HangingBreastFoldOptions& options) {
  const auto behind = fold_slice_behind_tip_mm(scan_vertices, tip, fitted_lowest, frame, height_mm, options);
  return behind && *behind < options.max_behind_tip_mm;
}

std::optional<Vec3> hanging_breast_fold_on_scan(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                                const SternumFrame& frame, double height_mm,
                                                const HangingBreastFoldOptions& options) {
  if (!(frame.length_mm > 0) || !(options.bin_mm > 0)) return std::nullopt;
  const auto strip = strip_of(scan_vertices, tip, fitted_lowest, frame, options);
  double h = height_mm;
  double front = front_most(strip, h, options.height_half_window_mm);
  if (!std::isfinite(front)) return std::nullopt;
  for (double below = options.bin_mm; below <= options.max_below_mm + 1e-9; below += options.bin_mm) {
    const double next_h = height_mm - below;
    const double next = front_most(strip, next_h, 0.5 * options.bin_mm);
    if (!std::isfinite(next)) continue;  // an empty slice (a hole): the next one decides
    if (front - next > options.min_fall_mm) {
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

std::optional<Vec3> lowest_breast_if_hanging(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                             const SternumFrame& frame, double height_mm,
                                             const HangingBreastFoldOptions& options) {
  if (!breast_hangs_over_fold(scan_vertices, tip, fitted_lowest, frame, height_mm, options)) return std::nullopt;
  return hanging_breast_fold_on_scan(scan_vertices, tip, fitted_lowest, frame, height_mm, options);
}

}  // namespace breastfit::fit
