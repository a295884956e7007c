#include "breastfit/mesh/body_frame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Dense>

#include "breastfit/core/errors.h"

namespace breastfit::mesh {

namespace {

std::optional<Vec3> find(const NamedPositions& lm, const std::string& name) {
  const auto it = lm.find(name);
  if (it == lm.end() || !it->second.allFinite()) return std::nullopt;
  return it->second;
}

std::optional<Vec3> midpoint(const NamedPositions& lm, const std::string& stem) {
  const auto r = find(lm, stem + "_R"), l = find(lm, stem + "_L");
  if (!r || !l) return std::nullopt;
  return 0.5 * (*r + *l);
}

Eigen::Matrix4d make_transform(const Vec3& x, const Vec3& y, const Vec3& z, const Vec3& origin) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.block<3, 1>(0, 0) = x;
  T.block<3, 1>(0, 1) = y;
  T.block<3, 1>(0, 2) = z;
  T.block<3, 1>(0, 3) = origin;
  return T;
}

/// Weighted samples of the shape: triangle centroids weighted by area, or vertices (weight 1).
struct Samples {
  std::vector<Vec3> p;
  std::vector<double> w;
};

Samples shape_samples(const TriangleMesh& mesh) {
  Samples s;
  if (mesh.F.rows() > 0) {
    s.p.reserve(static_cast<size_t>(mesh.F.rows()));
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t) {
      const Vec3 a = mesh.V.row(mesh.F(t, 0)), b = mesh.V.row(mesh.F(t, 1)), c = mesh.V.row(mesh.F(t, 2));
      const double area = 0.5 * (b - a).cross(c - a).norm();
      if (!(area > 0) || !std::isfinite(area)) continue;
      s.p.push_back((a + b + c) / 3.0);
      s.w.push_back(area);
    }
  }
  if (s.p.empty()) {
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
      const Vec3 v = mesh.V.row(i);
      if (!v.allFinite()) continue;
      s.p.push_back(v);
      s.w.push_back(1.0);
    }
  }
  return s;
}

/// Every k-th sample so that at most `n` remain (deterministic).
std::vector<Vec3> subsample(const std::vector<Vec3>& p, size_t n) {
  const size_t step = std::max<size_t>(1, (p.size() + n - 1) / n);
  std::vector<Vec3> out;
  for (size_t i = 0; i < p.size(); i += step) out.push_back(p[i]);
  return out;
}

/// Points sorted along one coordinate axis (the one of the largest extent), for nearest-point
/// queries that scan outward from the query's coordinate along it.
struct SortedPoints {
  int axis = 0;
  std::vector<Vec3> p;       ///< sorted by p[i][axis]
  std::vector<double> key;   ///< p[i][axis]
};

SortedPoints sorted_along_widest_axis(std::vector<Vec3> p) {
  SortedPoints s;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& q : p) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  (hi - lo).maxCoeff(&s.axis);
  const int axis = s.axis;
  std::sort(p.begin(), p.end(), [axis](const Vec3& a, const Vec3& b) { return a[axis] < b[axis]; });
  s.key.reserve(p.size());
  for (const Vec3& q : p) s.key.push_back(q[axis]);
  s.p = std::move(p);
  return s;
}

/// Mean distance from the mirror image of `probe` (across the plane through c with normal a) to
/// the nearest point of `target` (exhaustive in effect; both small). The scan along the sorted
/// axis stops once that coordinate's difference alone, squared, exceeds the best squared distance
/// so far: every point farther along has a squared distance at least that large (rounding is
/// monotone), so the minimum, and the sum, are the bits of the brute-force search over all pairs.
double mirror_asymmetry(const std::vector<Vec3>& probe, const SortedPoints& target, const Vec3& c, const Vec3& a) {
  double sum = 0;
  const size_t n = target.p.size();
  const int axis = target.axis;
  for (const Vec3& p : probe) {
    const Vec3 m = p - 2.0 * (p - c).dot(a) * a;
    double best = std::numeric_limits<double>::infinity();
    const double x = m[axis];
    const size_t start = static_cast<size_t>(std::lower_bound(target.key.begin(), target.key.end(), x) - target.key.begin());
    for (size_t j = start; j < n; ++j) {
      const double d = target.key[j] - x;
      if (d * d > best) break;
      best = std::min(best, (target.p[j] - m).squaredNorm());
    }
    for (size_t j = start; j-- > 0;) {
      const double d = target.key[j] - x;
      if (d * d > best) break;
      best = std::min(best, (target.p[j] - m).squaredNorm());
    }
    sum += std::sqrt(best);
  }
  return sum / static_cast<double>(probe.size());
}

/// The q-quantile of values weighted by their weights (0 when empty).
double weighted_percentile(std::vector<std::pair<double, double>> vw, double q) {
  if (vw.empty()) return 0.0;
  std::sort(vw.begin(), vw.end());
  double total = 0;
  for (const auto& [v, w] : vw) total += w;
  double acc = 0;
  for (const auto& [v, w] : vw) {
    acc += w;
    if (acc >= q * total) return v;
  }
  return vw.back().first;
}

}  // namespace

std::optional<BodyFrame> body_frame_from_landmarks(const NamedPositions& lm, double sternum_inclination_deg) {
  if (!std::isfinite(sternum_inclination_deg) || std::abs(sternum_inclination_deg) >= 60)
    throw InvalidInput("body_frame_from_landmarks: sternum_inclination_deg must be in (-60, 60), got " +
                       std::to_string(sternum_inclination_deg));
  std::string desc = "landmarks: ";
  std::vector<Vec3> used;
  Vec3 superior;
  bool from_sternum = false;
  const auto notch = find(lm, "sternal_notch"), xiphoid = find(lm, "xiphoid");
  if (notch && xiphoid && (*notch - *xiphoid).norm() > 0) {
    superior = *notch - *xiphoid;
    used.insert(used.end(), {*notch, *xiphoid});
    desc += "sternal_notch->xiphoid";
    from_sternum = true;
  } else {
    const auto top = midpoint(lm, "acromion");
    auto bottom = midpoint(lm, "lowest_breast");
    std::string bottom_name = "lowest_breast";
    if (!bottom) {
      bottom = midpoint(lm, "nipple");
      bottom_name = "nipple";
    }
    if (!top || !bottom || !((*top - *bottom).norm() > 0)) return std::nullopt;
    superior = *top - *bottom;
    used.insert(used.end(), {*top, *bottom});
    desc += "mid " + bottom_name + "->mid acromion";
  }
  Vec3 z = superior.normalized();

  std::optional<Vec3> x;
  for (const char* stem : {"acromion", "midaxillary", "pectoral_insertion", "nipple", "lowest_breast"}) {
    const auto r = find(lm, std::string(stem) + "_R"), l = find(lm, std::string(stem) + "_L");
    if (!r || !l) continue;
    const Vec3 d = *l - *r;
    const Vec3 ortho = d - d.dot(z) * z;
    // Reject pairs nearly parallel to the vertical (less than ~10° off it).
    if (!(ortho.norm() > 0.17 * d.norm()) || !(d.norm() > 0)) continue;
    x = ortho.normalized();
    used.insert(used.end(), {*r, *l});
    desc += std::string(", ") + stem + "_R->" + stem + "_L";
    break;
  }
  if (!x) return std::nullopt;
  Vec3 y = z.cross(*x);  // posterior
  if (from_sternum && sternum_inclination_deg != 0) {
    // Turn the sternal line about the left axis, top towards anterior (−y).
    const double a = sternum_inclination_deg * 3.14159265358979323846 / 180.0;
    z = std::cos(a) * z - std::sin(a) * y;
    y = z.cross(*x);
    desc += " (sternum inclination " + std::to_string(static_cast<int>(std::lround(sternum_inclination_deg))) + " deg)";
  }
  Vec3 origin = Vec3::Zero();
  if (notch) {
    origin = *notch;
  } else {
    for (const Vec3& p : used) origin += p;
    origin /= static_cast<double>(used.size());
  }
  return BodyFrame{make_transform(*x, y, z, origin), BodyFrameSource::Landmarks, desc};
}

BodyFrame body_frame_from_principal_axes(const TriangleMesh& mesh) {
  if (mesh.V.rows() < 4) throw InvalidInput("body_frame_from_principal_axes: need at least 4 vertices");
  const Samples s = shape_samples(mesh);
  double wsum = 0;
  Vec3 c = Vec3::Zero();
  for (size_t i = 0; i < s.p.size(); ++i) {
    c += s.w[i] * s.p[i];
    wsum += s.w[i];
  }
  if (!(wsum > 0)) throw InvalidInput("body_frame_from_principal_axes: the mesh has no extent");
  c /= wsum;
  Mat3 cov = Mat3::Zero();
  for (size_t i = 0; i < s.p.size(); ++i) {
    const Vec3 d = s.p[i] - c;
    cov += s.w[i] * d * d.transpose();
  }
  cov /= wsum;
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);  // ascending eigenvalues
  const Vec3 ev = eig.eigenvalues();
  if (!(ev[1] > 1e-9 * ev[2]) || !(ev[2] > 0))
    throw InvalidInput("body_frame_from_principal_axes: the shape is flat or a line");
  Vec3 ap = eig.eigenvectors().col(0);
  const Vec3 e2 = eig.eigenvectors().col(2);

  // Lateral axis: the normal of the best mirror-symmetry plane through the centroid, searched
  // over directions orthogonal to the antero-posterior axis (coarse 6° steps, then 1°), since
  // the in-plane principal axes are unreliable for cross-shaped crops (supine, arms abducted).
  const std::vector<Vec3> probe = subsample(s.p, 300);
  const SortedPoints target = sorted_along_widest_axis(subsample(s.p, 2000));
  const Vec3 u = e2.normalized(), v = ap.cross(u).normalized();
  auto direction = [&](double deg) {
    const double a = deg * 3.14159265358979323846 / 180.0;
    return Vec3(std::cos(a) * u + std::sin(a) * v);
  };
  double best_deg = 0, best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 30; ++k) {
    const double asym = mirror_asymmetry(probe, target, c, direction(6.0 * k));
    if (asym < best) best = asym, best_deg = 6.0 * k;
  }
  const double coarse = best_deg;
  for (int k = -5; k <= 5; ++k) {
    if (k == 0) continue;
    const double asym = mirror_asymmetry(probe, target, c, direction(coarse + k));
    if (asym < best) best = asym, best_deg = coarse + k;
  }
  const Vec3 lateral = direction(best_deg);
  Vec3 vertical = ap.cross(lateral).normalized();

  // Anterior sign: mean outward normal of a front-facing scan.
  Vec3 mean_normal = Vec3::Zero();
  double area_sum = 0;
  for (Eigen::Index t = 0; t < mesh.F.rows(); ++t) {
    const Vec3 a = mesh.V.row(mesh.F(t, 0)), b = mesh.V.row(mesh.F(t, 1)), cc = mesh.V.row(mesh.F(t, 2));
    const Vec3 n = 0.5 * (b - a).cross(cc - a);
    if (!n.allFinite()) continue;
    mean_normal += n;
    area_sum += n.norm();
  }
  if (mesh.F.rows() == 0 && mesh.has_normals()) {
    for (Eigen::Index i = 0; i < mesh.N.rows(); ++i) {
      mean_normal += mesh.N.row(i).transpose();
      area_sum += mesh.N.row(i).norm();
    }
  }
  std::string how;
  const double normal_bias = area_sum > 0 ? mean_normal.dot(ap) / area_sum : 0.0;
  if (std::abs(normal_bias) > 0.05) {
    if (normal_bias < 0) ap = -ap;
    how = "anterior from the mean normal";
  } else {
    // Extreme spread: the side reaching farther from the centroid (breasts) is anterior.
    double lo = 0, hi = 0;
    for (const Vec3& p : s.p) {
      const double t = (p - c).dot(ap);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    if (-lo > hi) ap = -ap;
    how = "anterior from the farther extreme";
  }
  // Superior sign: the end with the wider lateral extent (shoulders, arms), measured by the
  // area-weighted 95th percentile of |lateral offset| so that small fragments do not count.
  double vlo = std::numeric_limits<double>::infinity(), vhi = -vlo;
  for (const Vec3& p : s.p) {
    const double t = (p - c).dot(vertical);
    vlo = std::min(vlo, t);
    vhi = std::max(vhi, t);
  }
  const double third = (vhi - vlo) / 3.0;
  std::vector<std::pair<double, double>> low_end, high_end;  // (|lateral|, weight)
  for (size_t i = 0; i < s.p.size(); ++i) {
    const Vec3 d = s.p[i] - c;
    const double t = d.dot(vertical), w = std::abs(d.dot(lateral));
    if (t < vlo + third) low_end.emplace_back(w, s.w[i]);
    if (t > vhi - third) high_end.emplace_back(w, s.w[i]);
  }
  if (weighted_percentile(low_end, 0.95) > weighted_percentile(high_end, 0.95)) vertical = -vertical;

  const Vec3 z = vertical.normalized();
  const Vec3 y = (-ap - (-ap).dot(z) * z).normalized();  // posterior
  const Vec3 x = y.cross(z);                              // patient's left (right-handed LPS)
  return BodyFrame{make_transform(x, y, z, c), BodyFrameSource::PrincipalAxes,
                   "principal axes (" + how + ", superior = wider end)"};
}

BodyFrame estimate_body_frame(const TriangleMesh& mesh, const NamedPositions& landmarks,
                              double sternum_inclination_deg) {
  if (auto f = body_frame_from_landmarks(landmarks, sternum_inclination_deg)) return *f;
  return body_frame_from_principal_axes(mesh);
}

}  // namespace breastfit::mesh
