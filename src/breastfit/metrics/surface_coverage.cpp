#include "breastfit/metrics/surface_coverage.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "breastfit/mesh/normals.h"

namespace breastfit::metrics {

double SurfaceCoverage::fraction() const {
  return distance_mm.empty() ? 0.0 : static_cast<double>(covered_count) / static_cast<double>(distance_mm.size());
}

std::vector<double> SurfaceCoverage::covered_distances() const {
  std::vector<double> d;
  d.reserve(static_cast<size_t>(covered_count));
  for (size_t i = 0; i < distance_mm.size(); ++i)
    if (covered[i]) d.push_back(distance_mm[i]);
  return d;
}

DistanceStats SurfaceCoverage::stats() const { return distance_stats(covered_distances()); }

SurfaceCoverage surface_coverage(const TriangleMesh& fitted, const fit::ScanTarget& scan, const CoverageOptions& options,
                                 std::vector<Index>* hints) {
  SurfaceCoverage out;
  out.options = options;
  const Index n = fitted.V.rows();
  out.distance_mm.assign(static_cast<size_t>(n), std::numeric_limits<double>::infinity());
  out.covered.assign(static_cast<size_t>(n), 0);
  const Points N = fitted.F.rows() > 0 ? mesh::vertex_normals(fitted) : Points();
  const double cos_max = std::cos(options.max_normal_angle_deg * std::numbers::pi / 180.0);
  // Only the scan within max_distance_mm can cover a vertex: the searches stop there.
  std::vector<std::optional<fit::ScanMatch>> matches(static_cast<size_t>(n));
  const bool own_hints = hints && static_cast<Index>(hints->size()) == n;
  if (hints && !own_hints) hints->assign(static_cast<size_t>(n), -1);
  Index hint = -1;  // neighbouring vertices have neighbouring closest points: a warm start
  double agree = 0, disagree = 0;  // the scan's normals face the model's way, or the other
  for (Index i = 0; i < n; ++i) {
    Index* h = &hint;
    if (own_hints && (*hints)[static_cast<size_t>(i)] >= 0) h = &(*hints)[static_cast<size_t>(i)];
    auto& m = matches[static_cast<size_t>(i)] = scan.match(fitted.V.row(i).transpose(), options.max_distance_mm, h);
    if (!m) continue;
    if (h != &hint) hint = *h;
    if (hints) (*hints)[static_cast<size_t>(i)] = hint;
    out.distance_mm[static_cast<size_t>(i)] = std::sqrt(m->sq_dist);
    if (N.rows() == n && !m->on_boundary) (N.row(i).dot(m->normal.transpose()) >= 0 ? agree : disagree) += 1;
  }
  const double sign = agree >= disagree ? 1.0 : -1.0;
  for (Index i = 0; i < n; ++i) {
    if (!matches[static_cast<size_t>(i)]) continue;
    const fit::ScanMatch& m = *matches[static_cast<size_t>(i)];
    const double d = out.distance_mm[static_cast<size_t>(i)];
    if (options.skip_border && m.on_boundary) continue;
    if (d > options.max_distance_mm) continue;
    if (N.rows() == n && N.row(i).squaredNorm() > 0 && sign * N.row(i).dot(m.normal.transpose()) < cos_max) continue;
    const Vec3 offset = fitted.V.row(i).transpose() - m.point;
    if (d > options.direction_tolerance_mm && std::abs(offset.dot(m.normal)) < cos_max * d) continue;
    out.covered[static_cast<size_t>(i)] = 1;
    ++out.covered_count;
  }
  return out;
}

}  // namespace breastfit::metrics
