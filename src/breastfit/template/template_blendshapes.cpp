#include "breastfit/template/template_blendshapes.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/core/rng.h"
#include "breastfit/template/template_skeleton.h"

namespace breastfit::templ {
namespace {

double smoothstep(double e0, double e1, double x) {
  double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

Vec3 row(const Points& P, Index i) { return P.row(i).transpose(); }

model::Blendshape sparse_shape(std::string name, const Points& D, double lo, double hi) {
  model::Blendshape b;
  b.name = std::move(name);
  b.lo = lo;
  b.hi = hi;
  std::vector<Index> idx;
  for (Index v = 0; v < D.rows(); ++v)
    if (D.row(v).norm() > 1e-3) idx.push_back(v);
  b.vertices = idx;
  b.displacements.resize(static_cast<Index>(idx.size()), 3);
  for (size_t k = 0; k < idx.size(); ++k) b.displacements.row(static_cast<Index>(k)) = D.row(idx[k]);
  return b;
}

double weight_of(const model::SkinWeights& W, Index v, int bone) { return W.coeff(v, bone); }

const char* side_suffix(int side) { return side == 0 ? "_R" : "_L"; }

}  // namespace

Points template_normals(const TemplateMesh& tm, const BodyField& field) {
  const TriangleMesh& m = tm.mesh;
  Points N(m.num_vertices(), 3);
  for (Index v = 0; v < m.num_vertices(); ++v) {
    Vec3 n = field.normal(row(m.V, v));
    for (size_t c = 0; c < tm.cuts.size(); ++c) {
      if (tm.on_cut[v] & (1u << c)) {
        const Vec3& pn = tm.cuts[c].normal;
        n -= n.dot(pn) * pn;
      }
    }
    const double len = n.norm();
    N.row(v) = (len > 1e-9 ? Vec3(n / len) : Vec3::UnitZ()).transpose();
  }
  return N;
}

Points iso_displacement(const TemplateMesh& tm, const BodyField& rest, const BodyField& changed,
                        const Points& N) {
  const TriangleMesh& m = tm.mesh;
  Points D = Points::Zero(m.num_vertices(), 3);
  for (Index v = 0; v < m.num_vertices(); ++v) {
    const Vec3 p = row(m.V, v);
    const Vec3 n = row(N, v);
    const double f0 = rest.value(p);
    auto g = [&](double t) { return changed.value(p + t * n) - f0; };
    double g0 = g(0.0);
    if (std::abs(g0) < 1e-10) continue;
    double t = 0.0, gt = g0;
    bool ok = false;
    for (int it = 0; it < 30; ++it) {
      const double h = 0.05;
      const double dg = (g(t + h) - g(t - h)) / (2 * h);
      if (std::abs(dg) < 1e-6) break;
      double step = -gt / dg;
      step = std::clamp(step, -8.0, 8.0);
      t += step;
      gt = g(t);
      if (std::abs(gt) < 1e-6) {
        ok = true;
        break;
      }
    }
    if (!ok) {
      // Robust fallback: nearest sign change along the normal, then bisection.
      t = 0.0;
      for (double r = 0.5; r <= 60.0 && !ok; r += 0.5) {
        for (int sg = 1; sg >= -1 && !ok; sg -= 2) {
          const double a = sg * (r - 0.5), b = sg * r;
          double ga = g(a), gb = g(b);
          if ((ga <= 0) != (gb <= 0)) {
            double lo = a, hi = b;
            for (int k = 0; k < 40; ++k) {
              const double mid = 0.5 * (lo + hi);
              const double gm = g(mid);
              if ((gm <= 0) == (ga <= 0)) { lo = mid; ga = gm; } else { hi = mid; }
            }
            t = 0.5 * (lo + hi);
            ok = true;
          }
        }
      }
    }
    if (ok) D.row(v) = (t * n).transpose();
  }
  return D;
}

std::vector<model::Blendshape> template_blendshapes(const TemplateMesh& tm, const BodyField& field,
                                                    const model::SkinWeights& W, const Eigen::VectorXd& bh,
                                                    const BlendshapeOptions& o) {
  if (o.generic_modes < 0) throw InvalidInput("template blendshapes: generic_modes must be >= 0");
  const TriangleMesh& m = tm.mesh;
  const Index nv = m.num_vertices();
  const Points N = template_normals(tm, field);
  const BodyParams& P0 = field.params();
  struct Dense {
    std::string name;
    Points D;
    double lo, hi;
    int group;  // 0/1 = breast R/L, 2 = global, 3 = generic
  };
  std::vector<Dense> shapes;
  int group = 0;

  // Central-difference iso shape: weight 1 = the parameter moved by +delta.
  auto iso = [&](const std::string& name, const std::function<void(BodyParams&, double)>& change,
                 double lo, double hi) {
    BodyParams plus = P0, minus = P0;
    change(plus, 1.0);
    change(minus, -1.0);
    const Points Dp = iso_displacement(tm, field, BodyField(plus), N);
    const Points Dm = iso_displacement(tm, field, BodyField(minus), N);
    shapes.push_back({name, 0.5 * (Dp - Dm), lo, hi, group});
  };
  auto explicit_shape = [&](const std::string& name, const std::function<Vec3(Index)>& disp, double lo,
                            double hi) {
    Points D(nv, 3);
    for (Index v = 0; v < nv; ++v) D.row(v) = disp(v).transpose();
    shapes.push_back({name, D, lo, hi, group});
  };

  // ---- per breast ----
  for (int side = 0; side < 2; ++side) {
    group = side;
    const std::string sfx = side_suffix(side);
    const double s = side == 0 ? -1.0 : 1.0;
    const BreastFrame fr = field.breast_frame(side);
    const BreastParams& B = P0.breast[side];
    auto mound = [&](Index v) { return smoothstep(0.0, 25.0, bh[v]) * (m.V(v, 0) * s > 0 ? 1.0 : 0.0); };
    iso("breast_volume" + sfx,
        [side](BodyParams& p, double d) {
          auto& b = p.breast[side];
          const double k = 1.0 + 0.12 * d;
          b.radius_lateral *= k;
          b.radius_upper *= k;
          b.radius_lower *= k;
          b.depth *= k;
        },
        -1.5, 2.0);
    iso("breast_projection" + sfx, [side](BodyParams& p, double d) { p.breast[side].depth += 14.0 * d; }, -1.0,
        1.5);
    explicit_shape("breast_ptosis" + sfx,
                   [&, side](Index v) -> Vec3 {
                     const Vec3 q = row(m.V, v) - fr.center;
                     const double w = q.dot(fr.w);
                     const double phi = std::max(0.0, (w - B.sink) / std::max(B.depth - B.sink, 1.0));
                     (void)side;
                     return -18.0 * std::min(phi * phi, 1.5) * smoothstep(0.0, 6.0, bh[v]) *
                            (m.V(v, 0) * s > 0 ? 1.0 : 0.0) * fr.v;
                   },
                   -1.2, 2.5);
    // Wide ranges: supine breasts slide laterally by up to ~50 mm, and a ptotic breast sits
    // well below the template's.
    // Shifts of the whole breast: in proportion to the tissue's height above the chest wall (a
    // supine breast slides laterally by more where it is thicker), so the footprint's border
    // stretches instead of shearing into a crease...
    const double bh_top = std::max(1.0, bh.maxCoeff());
    auto thickness = [&](Index v) { return std::min(1.0, bh[v] / (0.6 * bh_top)) * (m.V(v, 0) * s > 0 ? 1.0 : 0.0); };
    explicit_shape("breast_lateral" + sfx, [&](Index v) -> Vec3 { return 15.0 * thickness(v) * Vec3(s, 0, 0); },
                   -1.0, 3.0);
    explicit_shape("breast_cranial" + sfx, [&](Index v) -> Vec3 { return 12.0 * thickness(v) * Vec3::UnitZ(); },
                   -2.5, 2.0);
    // ... and of the skin around it: a wide smooth field along the surface (the skin of the
    // lateral chest wall follows a supine breast towards the axilla).
    auto slide = [&](Index v, const Vec3& dir) -> Vec3 {
      const Vec3 p = row(m.V, v);
      const double g = std::exp(-(p - fr.base_center).squaredNorm() / (2.0 * 80.0 * 80.0));
      const Vec3 n = row(N, v);
      return g * smoothstep(0.0, 40.0, s * p.x()) * (dir - dir.dot(n) * n);
    };
    explicit_shape("breast_slide_lateral" + sfx, [&](Index v) -> Vec3 { return 12.0 * slide(v, Vec3(s, 0, 0)); },
                   -1.5, 1.5);
    explicit_shape("breast_slide_cranial" + sfx, [&](Index v) -> Vec3 { return 12.0 * slide(v, Vec3::UnitZ()); },
                   -2.0, 1.5);
    iso("breast_upper_pole" + sfx, [side](BodyParams& p, double d) { p.breast[side].upper_fullness += 0.2 * d; },
        -1.0, 1.0);
    iso("breast_lower_pole" + sfx, [side](BodyParams& p, double d) { p.breast[side].lower_fullness += 0.2 * d; },
        -1.0, 1.0);
    iso("imf_height" + sfx, [side](BodyParams& p, double d) { p.breast[side].radius_lower -= 10.0 * d; }, -1.0,
        1.0);
    iso("breast_width" + sfx, [side](BodyParams& p, double d) { p.breast[side].radius_lateral += 10.0 * d; },
        -1.0, 1.0);
    const Vec3 lat_dir = fr.u;
    explicit_shape("nipple_lateral" + sfx,
                   [&](Index v) -> Vec3 {
                     const double r2 = (row(m.V, v) - fr.nipple).squaredNorm();
                     Vec3 t = lat_dir - lat_dir.dot(row(N, v)) * row(N, v);
                     return 8.0 * std::exp(-r2 / (2 * 24.0 * 24.0)) * mound(v) * t;
                   },
                   -2.0, 2.0);
    explicit_shape("nipple_height" + sfx,
                   [&](Index v) -> Vec3 {
                     const double r2 = (row(m.V, v) - fr.nipple).squaredNorm();
                     Vec3 t = fr.v - fr.v.dot(row(N, v)) * row(N, v);
                     return 8.0 * std::exp(-r2 / (2 * 24.0 * 24.0)) * mound(v) * t;
                   },
                   -2.0, 2.0);
  }

  // ---- global ----
  group = 2;
  iso("chest_width", [](BodyParams& p, double d) { p.chest_width_scale += 0.05 * d; }, -1.0, 1.0);
  iso("chest_depth", [](BodyParams& p, double d) { p.chest_depth_scale += 0.06 * d; }, -1.0, 1.0);
  iso("waist_width", [](BodyParams& p, double d) { p.waist_width_scale += 0.06 * d; }, -1.0, 1.0);
  iso("hip_width", [](BodyParams& p, double d) { p.hip_width_scale += 0.06 * d; }, -1.0, 1.0);
  iso("abdomen_protrusion", [](BodyParams& p, double d) { p.abdomen_protrusion_mm += 12.0 * d; }, -1.0, 1.5);
  iso("back_curvature", [](BodyParams& p, double d) { p.kyphosis_mm += 12.0 * d; }, -1.0, 1.0);
  iso("upper_chest", [](BodyParams& p, double d) { p.upper_chest_mm += 8.0 * d; }, -1.0, 1.0);
  iso("back_width", [](BodyParams& p, double d) { p.back_width_scale += 0.05 * d; }, -1.0, 1.0);
  iso("shoulder_slope", [](BodyParams& p, double d) { p.shoulder_slope_mm += 10.0 * d; }, -1.0, 1.0);
  iso("neck_width", [](BodyParams& p, double d) { p.neck_radius_scale += 0.1 * d; }, -1.0, 1.0);
  for (int side = 0; side < 2; ++side) {
    group = side;  // sided shapes are orthogonalised within their side only (mirror symmetry)
    iso(std::string("arm_girth") + side_suffix(side),
        [side](BodyParams& p, double d) {
          auto& a = p.arm[side];
          a.radius_top += 5.0 * d;
          a.radius_mid += 5.0 * d;
          a.deltoid_radius += 4.0 * d;
        },
        -1.0, 1.0);
  }
  group = 2;
  explicit_shape("shoulder_width",
                 [&](Index v) -> Vec3 {
                   const double s = m.V(v, 0) < 0 ? -1.0 : 1.0;
                   const int c = s < 0 ? kClavicleR : kClavicleL, a = s < 0 ? kUpperArmR : kUpperArmL;
                   return 12.0 * (weight_of(W, v, c) + weight_of(W, v, a)) * Vec3(s, 0, 0);
                 },
                 -1.0, 1.0);
  // A belly that protrudes around the umbilicus (abdomen_protrusion moves the whole front of
  // the abdomen, which cannot make a rounded, pointed belly).
  explicit_shape("belly",
                 [&](Index v) -> Vec3 {
                   const Vec3 p = row(m.V, v);
                   const Vec3 n = row(N, v);
                   double hw, fy, by, ex;
                   field.trunk_profile(p.z(), &hw, &fy, &by, &ex);
                   const double front = smoothstep(0.5 * (fy + by), fy + 10.0, p.y());  // anterior half, smoothly
                   const double g = std::exp(-p.x() * p.x() / (2 * 85.0 * 85.0)) *
                                    std::exp(-(p.z() + 330.0) * (p.z() + 330.0) / (2 * 70.0 * 70.0));
                   const double below_folds = smoothstep(-235.0, -285.0, p.z());  // not into the breasts' creases
                   return 15.0 * g * front * below_folds * n;
                 },
                 -1.0, 2.0);
  explicit_shape("torso_length",
                 [&](Index v) -> Vec3 {
                   const double arms = weight_of(W, v, kUpperArmR) + weight_of(W, v, kUpperArmL);
                   return -20.0 * smoothstep(-60.0, P0.waist_cut_z, m.V(v, 2)) * (1.0 - arms) * Vec3::UnitZ();
                 },
                 -1.0, 1.0);

  // ---- generic smooth modes ----
  Rng rng(o.seed);
  for (int k = 0; k < o.generic_modes; ++k) {
    const bool sym = k % 2 == 0;
    std::vector<std::pair<Vec3, double>> bumps;
    for (int b = 0; b < 5; ++b) {
      const Index v = static_cast<Index>(rng.below(static_cast<std::uint64_t>(nv)));
      bumps.emplace_back(row(m.V, v), rng.normal());
    }
    auto phi = [&](const Vec3& p) {
      double s = 0;
      for (const auto& [c, a] : bumps)
        s += a * std::exp(-(p - c).squaredNorm() / (2 * o.generic_radius_mm * o.generic_radius_mm));
      return s;
    };
    Eigen::VectorXd val(nv);
    for (Index v = 0; v < nv; ++v) {
      const Vec3 p = row(m.V, v);
      const Vec3 q(-p.x(), p.y(), p.z());
      val[v] = sym ? phi(p) + phi(q) : phi(p) - phi(q);
    }
    const double mx = val.cwiseAbs().maxCoeff();
    if (mx > 1e-12) val *= o.generic_amplitude_mm / mx;
    Points D(nv, 3);
    for (Index v = 0; v < nv; ++v) D.row(v) = val[v] * N.row(v);
    char name[32];
    std::snprintf(name, sizeof name, "generic_%s_%02d", sym ? "sym" : "anti", k / 2);
    shapes.push_back({name, D, -1.0, 1.0, 3});
  }

  // Gram-Schmidt so that the shapes are not redundant: a breast/arm shape against the earlier
  // shapes of its side and a global shape against the earlier global ones when they overlap
  // (|cosine| > 0.25; smaller overlaps are kept so that local shapes stay local), each generic
  // mode against everything before it. Each result is rescaled to the largest displacement it had.
  for (size_t i = 0; i < shapes.size(); ++i) {
    Dense& si = shapes[i];
    const double max0 = si.D.rowwise().norm().maxCoeff();
    for (size_t j = 0; j < i; ++j) {
      const Dense& sj = shapes[j];
      if (si.group != 3 && sj.group != si.group) continue;
      const double nj = sj.D.squaredNorm();
      const double ni = si.D.squaredNorm();
      if (nj < 1e-12 || ni < 1e-12) continue;
      const double dot = si.D.cwiseProduct(sj.D).sum();
      if (si.group != 3 && std::abs(dot) < 0.25 * std::sqrt(ni * nj)) continue;
      si.D -= (dot / nj) * sj.D;
    }
    const double max1 = si.D.rowwise().norm().maxCoeff();
    if (max1 > 1e-9) si.D *= max0 / max1;
  }
  std::vector<model::Blendshape> out;
  for (const Dense& d : shapes) out.push_back(sparse_shape(d.name, d.D, d.lo, d.hi));
  return out;
}

}  // namespace breastfit::templ
