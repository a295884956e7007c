#include "breastfit/transfer/polyline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "breastfit/core/errors.h"

namespace breastfit::transfer {
namespace {

double segment_distance(const Vec3& q, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  double t = len2 > 0 ? (q - a).dot(ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return (q - (a + t * ab)).norm();
}

// P with the first point appended when closed (so that segments i → i+1 cover the loop).
Points unrolled(const Points& P, bool closed) {
  if (!closed || P.rows() < 2) return P;
  Points Q(P.rows() + 1, 3);
  Q.topRows(P.rows()) = P;
  Q.row(P.rows()) = P.row(0);
  return Q;
}

}  // namespace

double polyline_length(const Points& P, bool closed) {
  double len = 0;
  for (Eigen::Index i = 1; i < P.rows(); ++i) len += (P.row(i) - P.row(i - 1)).norm();
  if (closed && P.rows() > 2) len += (P.row(0) - P.row(P.rows() - 1)).norm();
  return len;
}

std::vector<double> arc_lengths(const Points& P) {
  std::vector<double> s(static_cast<size_t>(P.rows()), 0.0);
  for (Eigen::Index i = 1; i < P.rows(); ++i) s[i] = s[i - 1] + (P.row(i) - P.row(i - 1)).norm();
  return s;
}

Points resample_polyline(const Points& P, bool closed, double spacing) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw InvalidInput("resample_polyline: spacing must be > 0 (got " + std::to_string(spacing) + ")");
  if (P.rows() < 2) return P;
  const Points Q = unrolled(P, closed && P.rows() > 2);
  const std::vector<double> s = arc_lengths(Q);
  const double total = s.back();
  if (!(total > 0)) return P;
  Eigen::Index n;  // number of output points
  if (closed && P.rows() > 2)
    n = std::max<Eigen::Index>(3, static_cast<Eigen::Index>(std::llround(total / spacing)));
  else
    n = std::max<Eigen::Index>(2, static_cast<Eigen::Index>(std::ceil(total / spacing - 1e-9)) + 1);
  const double step = (closed && P.rows() > 2) ? total / static_cast<double>(n) : total / static_cast<double>(n - 1);
  Points out(n, 3);
  size_t seg = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = std::min(total, step * static_cast<double>(k));
    while (seg + 2 < s.size() && s[seg + 1] < t) ++seg;
    const double len = s[seg + 1] - s[seg];
    const double u = len > 0 ? std::clamp((t - s[seg]) / len, 0.0, 1.0) : 0.0;
    out.row(k) = (1 - u) * Q.row(seg) + u * Q.row(seg + 1);
  }
  if (!(closed && P.rows() > 2)) out.row(n - 1) = P.row(P.rows() - 1);
  return out;
}

Points laplacian_smooth(const Points& P, bool closed, double weight, const std::vector<bool>* fixed) {
  if (!(weight >= 0 && weight <= 1)) throw InvalidInput("laplacian_smooth: weight must be in [0, 1]");
  const Eigen::Index n = P.rows();
  Points out = P;
  if (n < 3) return out;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (fixed && (*fixed)[static_cast<size_t>(i)]) continue;
    Eigen::Index prev = i - 1, next = i + 1;
    if (!closed && (i == 0 || i == n - 1)) continue;
    if (prev < 0) prev = n - 1;
    if (next >= n) next = 0;
    out.row(i) = (1 - weight) * P.row(i) + weight * 0.5 * (P.row(prev) + P.row(next));
  }
  return out;
}

double point_polyline_distance(const Vec3& q, const Points& P, bool closed) {
  if (P.rows() == 0) throw InvalidInput("point_polyline_distance: empty polyline");
  if (P.rows() == 1) return (q - P.row(0).transpose()).norm();
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Index n = P.rows();
  const Eigen::Index segs = closed && n > 2 ? n : n - 1;
  for (Eigen::Index i = 0; i < segs; ++i)
    best = std::min(best, segment_distance(q, P.row(i).transpose(), P.row((i + 1) % n).transpose()));
  return best;
}

CurveDistance curve_distance(const Points& A, bool a_closed, const Points& B, bool b_closed, double spacing) {
  if (A.rows() == 0 || B.rows() == 0) throw InvalidInput("curve_distance: a curve has no points");
  const Points a = resample_polyline(A, a_closed, spacing);
  const Points b = resample_polyline(B, b_closed, spacing);
  CurveDistance d;
  auto directed = [](const Points& from, const Points& to, bool to_closed, double& mean, double& mx) {
    double sum = 0;
    for (Eigen::Index i = 0; i < from.rows(); ++i) {
      const double di = point_polyline_distance(from.row(i).transpose(), to, to_closed);
      sum += di;
      mx = std::max(mx, di);
    }
    mean = sum / static_cast<double>(from.rows());
  };
  double max_ab = 0, max_ba = 0;
  directed(a, b, b_closed, d.mean_a_to_b, max_ab);
  directed(b, a, a_closed, d.mean_b_to_a, max_ba);
  d.mean_sym = 0.5 * (d.mean_a_to_b + d.mean_b_to_a);
  d.hausdorff = std::max(max_ab, max_ba);
  return d;
}

}  // namespace breastfit::transfer
