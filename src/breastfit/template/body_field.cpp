#include "breastfit/template/body_field.h"

#include <algorithm>
#include <cmath>

#include "breastfit/core/errors.h"

namespace breastfit::templ {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

double smoothstep(double e0, double e1, double x) {
  double t = (x - e0) / (e1 - e0);
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// Polynomial smooth minimum with blend radius k (k <= 0: hard minimum).
double smin(double a, double b, double k) {
  if (k <= 0.0) return std::min(a, b);
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}

/// Distance-like value of an axis-aligned ellipsoid (radii r) at local q (iq's bound).
double ellipsoid_value(const Vec3& q, const Vec3& r) {
  const Vec3 a = q.cwiseQuotient(r);
  const Vec3 b = a.cwiseQuotient(r);
  const double k0 = a.norm();
  const double k1 = b.norm();
  if (k1 < 1e-12) return -r.minCoeff();
  return k0 * (k0 - 1.0) / k1;
}

/// Distance-like value of a 2D superellipse |x/a|^n + |y/b|^n = 1: (rho - 1) / |grad rho|.
double superellipse_value(double x, double y, double a, double b, double n) {
  const double ax = std::abs(x) / a + 1e-12;
  const double ay = std::abs(y) / b + 1e-12;
  const double px = std::pow(ax, n);
  const double py = std::pow(ay, n);
  const double rho = std::pow(px + py, 1.0 / n);
  // d rho / d x = rho^(1-n) * ax^(n-1) / a
  const double c = std::pow(rho, 1.0 - n);
  const double gx = c * std::pow(ax, n - 1.0) / a;
  const double gy = c * std::pow(ay, n - 1.0) / b;
  const double g = std::sqrt(gx * gx + gy * gy);
  return (rho - 1.0) / std::max(g, 1e-9);
}

/// Fritsch–Carlson monotone cubic slopes.
std::vector<double> pchip_slopes(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = x.size();
  std::vector<double> d(n - 1), m(n, 0.0);
  for (size_t i = 0; i + 1 < n; ++i) d[i] = (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
  m[0] = d[0];
  m[n - 1] = d[n - 2];
  for (size_t i = 1; i + 1 < n; ++i) {
    if (d[i - 1] * d[i] <= 0.0) {
      m[i] = 0.0;
    } else {
      const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
      const double w1 = 2 * h1 + h0, w2 = h1 + 2 * h0;
      m[i] = (w1 + w2) / (w1 / d[i - 1] + w2 / d[i]);
    }
  }
  return m;
}

double pchip_eval(const std::vector<double>& x, const std::vector<double>& y,
                  const std::vector<double>& m, double t) {
  const size_t n = x.size();
  if (t <= x[0]) return y[0] + m[0] * (t - x[0]) * 0.0;  // constant extension
  if (t >= x[n - 1]) return y[n - 1];
  size_t i = static_cast<size_t>(std::upper_bound(x.begin(), x.end(), t) - x.begin()) - 1;
  const double h = x[i + 1] - x[i];
  const double s = (t - x[i]) / h;
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * y[i] + (s3 - 2 * s2 + s) * h * m[i] + (-2 * s3 + 3 * s2) * y[i + 1] +
         (s3 - s2) * h * m[i + 1];
}

}  // namespace

bool CutPlane::in_region(const Vec3& p) const {
  if (!std::isfinite(region_radius)) return true;
  const Vec3 q = p - region_point;
  const Vec3 perp = q - q.dot(region_dir) * region_dir;
  return perp.norm() < region_radius;
}

BodyField::BodyField(const BodyParams& params) : params_(params) {
  auto knots = params_.trunk;
  if (knots.size() < 3) throw InvalidInput("body params: the trunk profile needs at least 3 knots");
  std::sort(knots.begin(), knots.end(), [](const TrunkKnot& a, const TrunkKnot& b) { return a.z < b.z; });
  for (size_t i = 0; i < knots.size(); ++i) {
    const auto& k = knots[i];
    if (!(k.half_width > 0) || !(k.back_y > k.front_y) || !(k.exponent >= 1.5))
      throw InvalidInput("body params: trunk knot " + std::to_string(i) +
                         " needs half_width > 0, back_y > front_y and exponent >= 1.5");
    if (i > 0 && !(k.z > knots[i - 1].z)) throw InvalidInput("body params: trunk knots need distinct z");
    kz_.push_back(k.z);
    kv_[0].push_back(k.half_width);
    kv_[1].push_back(k.front_y);
    kv_[2].push_back(k.back_y);
    kv_[3].push_back(k.exponent);
  }
  for (int c = 0; c < 4; ++c) ks_[c] = pchip_slopes(kz_, kv_[c]);

  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? -1.0 : 1.0;
    const ArmParams& a = params_.arm[side];
    joints_[side] = Vec3(s * a.joint_x, a.joint_y, a.joint_z);
    const double ab = a.abduction_deg * kDeg, fl = a.flexion_deg * kDeg;
    humerus_dirs_[side] =
        Vec3(s * std::sin(ab), -std::cos(ab) * std::sin(fl), -std::cos(ab) * std::cos(fl)).normalized();

    const BreastParams& b = params_.breast[side];
    BreastFrame& fr = breast_frames_[side];
    const double bx = s * b.base_x;
    fr.base_center = Vec3(bx, trunk_front_y(bx, b.base_z), b.base_z);
    const double la = b.axis_lateral_deg * kDeg, dn = b.axis_down_deg * kDeg;
    fr.w = Vec3(s * std::sin(la) * std::cos(dn), -std::cos(la) * std::cos(dn), -std::sin(dn)).normalized();
    Vec3 u = Vec3(s, 0, 0);
    u = (u - u.dot(fr.w) * fr.w).normalized();
    Vec3 v = fr.w.cross(u);
    if (v.z() < 0) v = -v;
    const double roll = b.roll_deg * kDeg;
    fr.u = std::cos(roll) * u - std::sin(roll) * v;
    fr.v = std::cos(roll) * v + std::sin(roll) * u;
    fr.center = fr.base_center - b.sink * fr.w;
    fr.nipple = fr.center + b.depth * fr.w - b.ptosis_mm * fr.v;
  }
}

void BodyField::trunk_profile(double z, double* hw, double* front, double* back, double* n) const {
  const BodyParams& P = params_;
  double w = pchip_eval(kz_, kv_[0], ks_[0], z);
  double f = pchip_eval(kz_, kv_[1], ks_[1], z);
  double b = pchip_eval(kz_, kv_[2], ks_[2], z);
  const double e = pchip_eval(kz_, kv_[3], ks_[3], z);
  // Global modifiers.
  const double chest = smoothstep(-290.0, -240.0, z) * (1.0 - smoothstep(-40.0, 0.0, z));
  w *= 1.0 + (P.chest_width_scale - 1.0) * chest;
  w *= 1.0 + (P.waist_width_scale - 1.0) * std::exp(-std::pow((z + 290.0) / 40.0, 2));
  w *= 1.0 + (P.hip_width_scale - 1.0) * smoothstep(-300.0, -370.0, z);
  const double depth = smoothstep(-300.0, -250.0, z) * (1.0 - smoothstep(-40.0, 0.0, z));
  const double yc = 0.5 * (f + b);
  const double ds = 1.0 + (P.chest_depth_scale - 1.0) * depth;
  f = yc + (f - yc) * ds;
  b = yc + (b - yc) * ds;
  f -= P.abdomen_protrusion_mm * smoothstep(-230.0, -330.0, z);
  f -= P.upper_chest_mm * std::exp(-std::pow((z + 70.0) / 45.0, 2));
  b += P.kyphosis_mm * std::exp(-std::pow((z + 90.0) / 70.0, 2));
  *hw = w;
  *front = f;
  *back = b;
  *n = e;
}

double BodyField::trunk_value(const Vec3& p) const {
  const BodyParams& P = params_;
  // Shoulder slope: shift the trunk profile up at the shoulders.
  const double ax = std::abs(p.x());
  const double lift = P.shoulder_slope_mm * smoothstep(45.0, 120.0, ax) * smoothstep(-90.0, -10.0, p.z());
  double w, f, b, n;
  trunk_profile(p.z() - lift, &w, &f, &b, &n);
  const double yc = 0.5 * (f + b);
  const double dy = p.y() - yc;
  const double half_depth = 0.5 * (b - f);
  const double back = smoothstep(-30.0, 30.0, dy) * smoothstep(-300.0, -250.0, p.z()) *
                      (1.0 - smoothstep(-60.0, -20.0, p.z()));
  w *= 1.0 + (P.back_width_scale - 1.0) * back;
  return superellipse_value(p.x(), dy, w, half_depth, n);
}

double BodyField::neck_value(const Vec3& p) const {
  const BodyParams& P = params_;
  const double t = P.neck_tilt_deg * kDeg;
  const Vec3 axis(0.0, -std::sin(t), std::cos(t));
  const Vec3 base(0.0, P.neck_center_y, 0.0);
  const Vec3 q = p - base;
  const double h = q.dot(axis);
  const Vec3 yaxis = Vec3::UnitX().cross(axis);  // (0, cos, sin)... orthogonal to x and axis
  const double lx = q.x();
  const double ly = q.dot(yaxis);
  const double v = superellipse_value(lx, ly, P.neck_radius_x * P.neck_radius_scale,
                                      P.neck_radius_y * P.neck_radius_scale, 2.0);
  return std::max(v, -80.0 - h);  // capped inside the trunk
}

double BodyField::arm_value(const Vec3& p, int side) const {
  const ArmParams& a = params_.arm[side];
  const Vec3& J = joints_[side];
  const Vec3& d = humerus_dirs_[side];
  const double s = side == 0 ? -1.0 : 1.0;
  const double t = std::clamp((p - J).dot(d), -10.0, a.cut_length + 90.0);
  const double frac = std::clamp(t / a.cut_length, 0.0, 1.3);
  const double r = a.radius_top + (a.radius_mid - a.radius_top) * frac;
  const double arm = (p - (J + t * d)).norm() - r;
  const Vec3 dc = J + Vec3(s * 6.0, 4.0, 4.0);
  const double delt =
      ellipsoid_value(p - dc, Vec3(a.deltoid_radius, a.deltoid_radius, a.deltoid_height));
  return smin(arm, delt, 0.6 * params_.blend_arm_mm);
}

double BodyField::breast_value(const Vec3& p, int side) const {
  const BreastParams& b = params_.breast[side];
  const BreastFrame& fr = breast_frames_[side];
  const Vec3 q = p - fr.center;
  const double u = q.dot(fr.u);
  double v = q.dot(fr.v);
  const double w = q.dot(fr.w);
  const double phi = std::max(0.0, (w - b.sink) / std::max(b.depth - b.sink, 1.0));
  v += b.ptosis_mm * phi * phi;
  const double full = 1.0 + b.upper_fullness * smoothstep(0.0, 0.6 * b.radius_upper, v) +
                      b.lower_fullness * smoothstep(0.0, 0.6 * b.radius_lower, -v);
  const double w_eff = w / std::max(full, 0.2);
  const double rv = v > 0 ? b.radius_upper * (1.0 - b.upper_slope * std::min(phi, 1.0)) : b.radius_lower;
  return ellipsoid_value(Vec3(u, v, w_eff), Vec3(b.radius_lateral, rv, b.depth));
}

double BodyField::body_value(const Vec3& p, bool with_breasts) const {
  const BodyParams& P = params_;
  double f = smin(trunk_value(p), neck_value(p), P.blend_neck_mm);
  for (int side = 0; side < 2; ++side) {
    // Skip the far side: each arm only matters on its own half.
    if ((side == 0 && p.x() > 60.0) || (side == 1 && p.x() < -60.0)) continue;
    const Vec3& J = joints_[side];
    // Smaller blend below the shoulder so the axilla stays a hollow, not a web.
    const double kz = smoothstep(J.z() - 120.0, J.z() - 30.0, p.z());
    const double k = 8.0 + (P.blend_arm_mm - 8.0) * kz;
    f = smin(f, arm_value(p, side), k);
  }
  if (with_breasts) {
    for (int side = 0; side < 2; ++side) {
      if ((side == 0 && p.x() > 40.0) || (side == 1 && p.x() < -40.0)) continue;
      const BreastParams& b = P.breast[side];
      const BreastFrame& fr = breast_frames_[side];
      const double v = (p - fr.center).dot(fr.v);
      const double k = b.blend_lower_mm + (b.blend_upper_mm - b.blend_lower_mm) * smoothstep(-70.0, 50.0, v);
      f = smin(f, breast_value(p, side), k);
    }
  }
  return f;
}

double BodyField::value(const Vec3& p) const { return body_value(p, true); }
double BodyField::value_without_breasts(const Vec3& p) const { return body_value(p, false); }

Vec3 BodyField::gradient(const Vec3& p) const {
  const double h = 0.05;
  Vec3 g;
  for (int i = 0; i < 3; ++i) {
    Vec3 a = p, b = p;
    a[i] += h;
    b[i] -= h;
    g[i] = (value(a) - value(b)) / (2 * h);
  }
  return g;
}

Vec3 BodyField::normal(const Vec3& p) const {
  const Vec3 g = gradient(p);
  const double n = g.norm();
  return n > 1e-12 ? Vec3(g / n) : Vec3(Vec3::UnitZ());
}

Vec3 BodyField::project(const Vec3& p0, int iterations) const {
  Vec3 p = p0;
  for (int it = 0; it < iterations; ++it) {
    const double f = value(p);
    if (std::abs(f) < 1e-7) break;
    const Vec3 g = gradient(p);
    const double g2 = g.squaredNorm();
    if (g2 < 1e-12) break;
    Vec3 step = f * g / g2;
    const double len = step.norm();
    if (len > 20.0) step *= 20.0 / len;
    p -= step;
  }
  return p;
}

Vec3 BodyField::project_on_plane(const Vec3& p0, const Vec3& c, const Vec3& n, int iterations) const {
  Vec3 p = p0 - n.dot(p0 - c) * n;
  for (int it = 0; it < iterations; ++it) {
    const double f = value(p);
    if (std::abs(f) < 1e-7) break;
    Vec3 g = gradient(p);
    g -= g.dot(n) * n;
    const double g2 = g.squaredNorm();
    if (g2 < 1e-12) break;
    Vec3 step = f * g / g2;
    const double len = step.norm();
    if (len > 20.0) step *= 20.0 / len;
    p -= step;
    p -= n.dot(p - c) * n;
  }
  return p;
}

Vec3 BodyField::project_on_two_planes(const Vec3& p0, const CutPlane& a, const CutPlane& b,
                                      int iterations) const {
  // Point on both planes closest to p0, then move along the planes' intersection line.
  Vec3 dir = a.normal.cross(b.normal);
  const double dn = dir.norm();
  if (dn < 1e-9) return project_on_plane(p0, a.point, a.normal, iterations);
  dir /= dn;
  // Solve for the point on both planes nearest to p0: p = p0 + x a.n + y b.n.
  Eigen::Matrix2d M;
  M << a.normal.dot(a.normal), a.normal.dot(b.normal), b.normal.dot(a.normal), b.normal.dot(b.normal);
  const Eigen::Vector2d rhs(-a.signed_distance(p0), -b.signed_distance(p0));
  const Eigen::Vector2d xy = M.fullPivLu().solve(rhs);
  Vec3 p = p0 + xy[0] * a.normal + xy[1] * b.normal;
  for (int it = 0; it < iterations; ++it) {
    const double f = value(p);
    if (std::abs(f) < 1e-7) break;
    const double gd = gradient(p).dot(dir);
    if (std::abs(gd) < 1e-9) break;
    double step = f / gd;
    step = std::clamp(step, -20.0, 20.0);
    p -= step * dir;
  }
  return p;
}

double BodyField::ray_root(const Vec3& p, const Vec3& d, double max_t) const {
  // March outwards in both directions from t = 0 looking for the nearest sign change.
  const double f0 = value(p);
  if (f0 == 0.0) return 0.0;
  const double dt = 1.0;
  for (double t = dt; t <= max_t + 1e-9; t += dt) {
    for (int sgn = 1; sgn >= -1; sgn -= 2) {
      const double t1 = sgn * t, t0 = sgn * (t - dt);
      const double f1 = value(p + t1 * d);
      if ((f1 <= 0.0) != (f0 <= 0.0)) {
        double a = t0, b = t1, fa = value(p + a * d);
        for (int it = 0; it < 40; ++it) {
          const double m = 0.5 * (a + b);
          const double fm = value(p + m * d);
          if ((fm <= 0.0) == (fa <= 0.0)) {
            a = m;
            fa = fm;
          } else {
            b = m;
          }
        }
        return 0.5 * (a + b);
      }
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double BodyField::trunk_front_y(double x, double z) const {
  double w, f, b, n;
  trunk_profile(z, &w, &f, &b, &n);
  const double yc = 0.5 * (f + b);
  // Bisection on y in [f - 50, yc] for trunk_value = 0 (inside at yc when |x| < w).
  double lo = f - 60.0, hi = yc;
  const Vec3 pin(x, hi, z);
  if (trunk_value(pin) > 0) return f;
  for (int it = 0; it < 60; ++it) {
    const double m = 0.5 * (lo + hi);
    if (trunk_value(Vec3(x, m, z)) > 0) lo = m; else hi = m;
  }
  return 0.5 * (lo + hi);
}

CutPlane BodyField::waist_cut() const {
  CutPlane c;
  c.point = Vec3(0, 0, params_.waist_cut_z);
  c.normal = -Vec3::UnitZ();
  return c;
}

CutPlane BodyField::neck_cut() const {
  const BodyParams& P = params_;
  CutPlane c;
  const double t = P.neck_cut_tilt_deg * kDeg;
  c.point = Vec3(0, P.neck_center_y, P.neck_cut_z);
  c.normal = Vec3(0.0, -std::sin(t), std::cos(t));
  const double nt = P.neck_tilt_deg * kDeg;
  c.region_point = Vec3(0.0, P.neck_center_y, 0.0);
  c.region_dir = Vec3(0.0, -std::sin(nt), std::cos(nt));
  c.region_radius = 1.9 * std::max(P.neck_radius_x, P.neck_radius_y) * P.neck_radius_scale;
  return c;
}

CutPlane BodyField::arm_cut(int side) const {
  const ArmParams& a = params_.arm[side];
  CutPlane c;
  c.normal = humerus_dirs_[side];
  c.point = joints_[side] + a.cut_length * c.normal;
  c.region_point = joints_[side];
  c.region_dir = c.normal;
  c.region_radius = a.radius_mid + 24.0;
  return c;
}

std::vector<CutPlane> BodyField::cut_planes() const {
  return {waist_cut(), neck_cut(), arm_cut(0), arm_cut(1)};
}

}  // namespace breastfit::templ
