#include "breastfit/fit/jugular_notch.h"

#include <cmath>
#include <limits>
#include <vector>

namespace breastfit::fit {
namespace {

// Least-squares line residual (sum of squares) and slope of points (x, y); x = height, y = depth.
struct LineFit {
  double sse = 0, slope = 0;
};

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y, size_t begin, size_t end) {
  const double n = static_cast<double>(end - begin);
  double sx = 0, sy = 0;
  for (size_t i = begin; i < end; ++i) sx += x[i], sy += y[i];
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0, syy = 0;
  for (size_t i = begin; i < end; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  LineFit f;
  f.slope = sxx > 0 ? sxy / sxx : 0.0;
  f.sse = std::max(0.0, syy - f.slope * sxy);
  return f;
}

}  // namespace

std::optional<Vec3> jugular_notch_on_scan(const Points& scan_vertices, const Vec3& fitted_notch, const Vec3& up,
                                          const Vec3& front, const JugularNotchOptions& options) {
  const Vec3 side = up.cross(front).normalized();
  const int bins = static_cast<int>(std::ceil((options.below_mm + options.above_mm) / options.bin_mm));
  if (bins <= 0) return std::nullopt;
  // The most anterior scan vertex of the midline strip in each height bin.
  std::vector<Index> front_most(bins, -1);
  std::vector<double> depth(bins, -std::numeric_limits<double>::infinity());
  for (Index i = 0; i < scan_vertices.rows(); ++i) {
    const Vec3 d = scan_vertices.row(i).transpose() - fitted_notch;
    if (std::abs(d.dot(side)) > options.strip_half_width_mm) continue;
    const double h = d.dot(up) + options.below_mm;
    if (h < 0) continue;
    const int b = static_cast<int>(h / options.bin_mm);
    if (b >= bins) continue;
    const double y = d.dot(front);
    if (y < -options.max_behind_mm) continue;
    if (y > depth[b]) {
      depth[b] = y;
      front_most[b] = i;
    }
  }
  // The profile from the first filled bin up to the first long hole (the neck's cut).
  std::vector<double> height, front_depth;
  std::vector<Index> vertex;
  int last = -1;
  for (int b = 0; b < bins; ++b) {
    if (front_most[b] < 0) continue;
    if (last >= 0 && (b - last - 1) * options.bin_mm > options.max_gap_mm) break;
    const Vec3 p = scan_vertices.row(front_most[b]).transpose() - fitted_notch;
    height.push_back(p.dot(up));
    front_depth.push_back(p.dot(front));
    vertex.push_back(front_most[b]);
    last = b;
  }
  const size_t n = height.size(), m = static_cast<size_t>(options.min_bins_each_side);
  if (n < 2 * m) return std::nullopt;
  // The break with the smallest two-line residual; the sternum below recedes (depth falls going
  // up), the neck above does not, or much less.
  double best = std::numeric_limits<double>::infinity();
  std::optional<size_t> knee;
  for (size_t k = m; k + m <= n; ++k) {
    const LineFit below = fit_line(height, front_depth, 0, k + 1), above = fit_line(height, front_depth, k, n);
    if (above.slope - below.slope < options.min_slope_change) continue;
    if (below.sse + above.sse < best) {
      best = below.sse + above.sse;
      knee = k;
    }
  }
  if (!knee) return std::nullopt;
  // On the fitted midline: the strip gives the notch's height and depth, its front-most vertex may
  // lie up to the strip's half-width to one side.
  const Vec3 p = scan_vertices.row(vertex[*knee]).transpose();
  return Vec3(p - (p - fitted_notch).dot(side) * side);
}

}  // namespace breastfit::fit
