#include "breastfit/synth/truth_curves.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "breastfit/core/errors.h"

namespace breastfit::synth {
namespace {

/// Points every `step` along the polyline (closed: including the closing segment), first point
/// included; an open polyline also gets its last point.
std::vector<Vec3> walk(const std::vector<Vec3>& pts, bool closed, double step, bool uniform) {
  std::vector<Vec3> seg = pts;
  if (closed) seg.push_back(pts.front());
  std::vector<double> cum(seg.size(), 0.0);
  for (size_t i = 1; i < seg.size(); ++i) cum[i] = cum[i - 1] + (seg[i] - seg[i - 1]).norm();
  const double total = cum.back();
  std::vector<Vec3> out;
  if (total <= 0) return {pts.front()};
  int n = std::max(1, static_cast<int>(std::round(total / step)));
  if (!uniform) n = std::max(1, static_cast<int>(std::ceil(total / step)));
  const double h = total / n;
  const int count = closed ? n : n + 1;
  size_t s = 1;
  for (int k = 0; k < count; ++k) {
    const double d = std::min(k * h, total);
    while (s + 1 < seg.size() && cum[s] < d) ++s;
    const double len = cum[s] - cum[s - 1];
    const double t = len > 0 ? (d - cum[s - 1]) / len : 0.0;
    out.push_back(seg[s - 1] + std::clamp(t, 0.0, 1.0) * (seg[s] - seg[s - 1]));
  }
  return out;
}

void project(std::vector<Vec3>& pts, const spatial::ClosestPointIndex& surface) {
  for (Vec3& p : pts) p = surface.closest(p).point;
}

}  // namespace

Points resample_on_surface(const Points& P, bool closed, const spatial::ClosestPointIndex& surface,
                           double spacing_mm) {
  if (P.rows() < 2) throw InvalidInput("resample_on_surface: a curve needs at least 2 points");
  if (!(spacing_mm > 0)) throw InvalidInput("resample_on_surface: spacing must be > 0");
  std::vector<Vec3> pts;
  for (Index i = 0; i < P.rows(); ++i) pts.push_back(P.row(i).transpose());
  // Densify to a quarter of the spacing and follow the surface, then resample uniformly.
  std::vector<Vec3> dense = walk(pts, closed, 0.25 * spacing_mm, false);
  project(dense, surface);
  std::vector<Vec3> out = walk(dense, closed, spacing_mm, true);
  project(out, surface);
  Points R(static_cast<Index>(out.size()), 3);
  for (size_t i = 0; i < out.size(); ++i) R.row(static_cast<Index>(i)) = out[i].transpose();
  return R;
}

}  // namespace breastfit::synth
