#include "breastfit/metrics/truth_errors.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "breastfit/spatial/closest_point_index.h"

namespace breastfit::metrics {
namespace {

Points resample(const Curve& c, double spacing) {
  std::vector<Vec3> out;
  const Index n = c.points.rows();
  const Index segments = c.closed ? n : n - 1;
  for (Index i = 0; i < segments; ++i) {
    const Vec3 a = c.points.row(i).transpose();
    const Vec3 b = c.points.row((i + 1) % n).transpose();
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing)));
    for (int k = 0; k < steps; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / steps));
  }
  if (!c.closed && n > 0) out.push_back(c.points.row(n - 1).transpose());
  Points P(out.size(), 3);
  for (size_t i = 0; i < out.size(); ++i) P.row(i) = out[i].transpose();
  return P;
}

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double directed_mean(const Points& from, const Curve& to) {
  if (from.rows() == 0 || to.points.rows() == 0) return std::numeric_limits<double>::infinity();
  const Index n = to.points.rows();
  const Index segments = to.closed ? n : std::max<Index>(n - 1, 1);
  double sum = 0;
  for (Index i = 0; i < from.rows(); ++i) {
    const Vec3 p = from.row(i).transpose();
    double best = std::numeric_limits<double>::infinity();
    for (Index s = 0; s < segments; ++s)
      best = std::min(best, point_segment_distance(p, to.points.row(s).transpose(),
                                                   to.points.row((s + 1) % n).transpose()));
    sum += best;
  }
  return sum / from.rows();
}

}  // namespace

TruthErrors truth_errors(const Points& fitted_V, const TriangleMesh& truth, const fit::ScanTarget& scan,
                         const std::vector<NamedPoint>& model_landmarks,
                         const std::vector<NamedPoint>& truth_landmarks, double observed_mm) {
  return truth_errors(fitted_V, spatial::ClosestPointIndex(truth), scan, model_landmarks, truth_landmarks,
                      observed_mm);
}

TruthErrors truth_errors(const Points& fitted_V, const spatial::ClosestPointIndex& index, const fit::ScanTarget& scan,
                         const std::vector<NamedPoint>& model_landmarks,
                         const std::vector<NamedPoint>& truth_landmarks, double observed_mm) {
  TruthErrors out;
  std::vector<double> d;
  for (Index i = 0; i < fitted_V.rows(); ++i) {
    const auto cp = index.closest(fitted_V.row(i).transpose());
    if (cp.on_boundary) continue;
    if (!scan.match(cp.point, observed_mm)) continue;  // that part of the truth was not scanned
    d.push_back(std::sqrt(cp.sq_dist));
  }
  out.surface = distance_stats(d);
  std::vector<double> l;
  for (const auto& m : model_landmarks)
    for (const auto& t : truth_landmarks)
      if (m.name == t.name) l.push_back((m.position - t.position).norm());
  out.landmarks = distance_stats(l);
  return out;
}

double curve_distance(const Curve& a, const Curve& b, double spacing_mm) {
  const Points pa = resample(a, spacing_mm);
  const Points pb = resample(b, spacing_mm);
  return 0.5 * (directed_mean(pa, b) + directed_mean(pb, a));
}

}  // namespace breastfit::metrics
