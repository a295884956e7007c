#include "breastfit/fit/breast_fold.h"

#include <cmath>
#include <limits>
#include <vector>

namespace breastfit::fit {

std::optional<Vec3> lowest_breast_on_scan(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                          const Vec3& up, const Vec3& front, const BreastFoldOptions& options) {
  const Vec3 side = up.cross(front).normalized();
  const double strip_centre = (fitted_lowest - tip).dot(side);
  const int bins = static_cast<int>(std::ceil((options.max_drop_mm - options.min_drop_mm) / options.bin_mm));
  if (bins <= 0) return std::nullopt;
  // The most anterior scan vertex of the strip in each height bin below the tip.
  std::vector<Index> front_most(bins, -1);
  std::vector<double> depth(bins, -std::numeric_limits<double>::infinity());
  for (Index i = 0; i < scan_vertices.rows(); ++i) {
    const Vec3 d = scan_vertices.row(i).transpose() - tip;
    if (std::abs(d.dot(side) - strip_centre) > options.strip_half_width_mm) continue;
    const double drop = -d.dot(up) - options.min_drop_mm;
    if (drop < 0) continue;
    const int b = static_cast<int>(drop / options.bin_mm);
    if (b >= bins) continue;
    const double y = d.dot(front);
    if (y > depth[b]) {
      depth[b] = y;
      front_most[b] = i;
    }
  }
  // Going down: the first bin whose front-most skin is the fold's depth behind the tip, seen
  // crossing (the bin before it in front of that depth) without a long hole on the way.
  const double target = -options.depth_behind_tip_mm;
  int last = -1;
  for (int b = 0; b < bins; ++b) {
    if (front_most[b] < 0) continue;
    if (last < 0 && depth[b] <= target) return std::nullopt;  // starts behind the fold: not a breast
    if (last >= 0 && (b - last) * options.bin_mm > options.max_gap_mm) return std::nullopt;
    if (depth[b] <= target) {
      // Between the two profile points, at the fold's depth.
      const Vec3 a = scan_vertices.row(front_most[last]).transpose();
      const Vec3 c = scan_vertices.row(front_most[b]).transpose();
      const double t = (depth[last] - target) / (depth[last] - depth[b]);
      const Vec3 fold = a + t * (c - a);
      if ((fitted_lowest - fold).dot(up) > options.max_below_fitted_mm) return std::nullopt;
      return fold;
    }
    last = b;
  }
  return std::nullopt;
}

double lowest_breast_drop_mm(const SternumFrame& frame, double nipple_drop_mm,
                             const BreastFoldProportionOptions& options) {
  const double by_sternum = options.sternum_drop * frame.length_mm;
  const double by_nipple = options.nipple_slope * nipple_drop_mm + options.nipple_offset_mm;
  return (1 - options.nipple_share) * by_sternum + options.nipple_share * by_nipple;
}

std::optional<Vec3> lowest_breast_by_proportion(const Points& scan_vertices, const Vec3& tip, const Vec3& fitted_lowest,
                                                const SternumFrame& frame, const BreastFoldProportionOptions& options) {
  if (!(frame.length_mm > 0)) return std::nullopt;
  const SternumCoordinates fitted = sternum_coordinates(frame, fitted_lowest);
  const SternumCoordinates at_tip = sternum_coordinates(frame, tip);
  const double height = -lowest_breast_drop_mm(frame, -at_tip.height, options);
  const double front_limit = at_tip.front + options.max_in_front_of_tip_mm;
  Index best = -1;
  double front = -std::numeric_limits<double>::infinity();
  for (Index i = 0; i < scan_vertices.rows(); ++i) {
    const SternumCoordinates p = sternum_coordinates(frame, scan_vertices.row(i).transpose());
    if (std::abs(p.height - height) > options.height_half_window_mm ||
        std::abs(p.lateral - fitted.lateral) > options.strip_half_width_mm || p.front > front_limit || p.front <= front)
      continue;
    front = p.front;
    best = i;
  }
  if (best < 0) return std::nullopt;
  const Vec3 found = scan_vertices.row(best).transpose();
  if ((found - fitted_lowest).norm() > options.max_shift_mm) return std::nullopt;
  return found;
}

}  // namespace breastfit::fit
