#include "breastfit/pipeline/fit_deviation.h"

#include <algorithm>

#include "breastfit/core/errors.h"
#include "breastfit/transfer/polyline.h"

namespace breastfit::pipeline {
namespace {

// The largest distance of a point of `from` to the polyline of `to`.
double farthest_point(const transfer::TransferredCurve& from, const transfer::TransferredCurve& to) {
  double d = 0;
  for (Eigen::Index i = 0; i < from.points.rows(); ++i)
    d = std::max(d, transfer::point_polyline_distance(from.points.row(i).transpose(), to.points, to.closed));
  return d;
}

}  // namespace

FitDeviation fit_deviation(const RegisterResult& a, const RegisterResult& b) {
  if (a.fit.vertices.rows() != b.fit.vertices.rows())
    throw InvalidInput("fit_deviation: the fits have " + std::to_string(a.fit.vertices.rows()) + " and " +
                       std::to_string(b.fit.vertices.rows()) + " vertices (not the same template)");
  FitDeviation out;
  std::vector<double> d(static_cast<size_t>(a.fit.vertices.rows()));
  for (Eigen::Index i = 0; i < a.fit.vertices.rows(); ++i)
    d[static_cast<size_t>(i)] = (a.fit.vertices.row(i) - b.fit.vertices.row(i)).norm();
  if (!d.empty()) {
    out.surface_max_mm = *std::max_element(d.begin(), d.end());
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
    out.surface_median_mm = d[d.size() / 2];
  }
  for (const auto& p : a.model_landmarks_mm.points)
    for (const auto& q : b.model_landmarks_mm.points)
      if (p.name == q.name) out.landmarks_max_mm = std::max(out.landmarks_max_mm, (p.position - q.position).norm());
  for (const auto& c : a.drawings_on_scan)
    for (const auto& e : b.drawings_on_scan)
      if (c.name == e.name && c.points.rows() > 1 && e.points.rows() > 1)
        out.drawings_max_mm = std::max({out.drawings_max_mm, farthest_point(c, e), farthest_point(e, c)});
  return out;
}

}  // namespace breastfit::pipeline
