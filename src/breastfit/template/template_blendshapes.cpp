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

namespace {

/// A shape before orthogonalisation: dense displacements (#V by 3) at weight 1.
struct DenseShape {
  std::string name;
  Points D;
  double lo, hi;
  int group;  // 0/1 = breast R/L (and the sided arm shape), 2 = global, 3 = generic
};

/// The semantic shapes and generic modes of the template, in the order they are added.
class ShapeBuilder {
 public:
  ShapeBuilder(const TemplateMesh& tm, const BodyField& field, const model::SkinWeights& W, const Eigen::VectorXd& bh)
      : tm_(tm), m_(tm.mesh), field_(field), W_(W), bh_(bh), nv_(m_.num_vertices()), N_(template_normals(tm, field)),
        P0_(field.params()) {}

  /// Per breast (side 0 = R, 1 = L): size, shifts, contour and nipple shapes.
  void add_breast_shapes(int side) {
    group_ = side;
    add_breast_size_shapes(side);
    add_breast_shift_shapes(side);
    add_breast_contour_shapes(side);
    add_nipple_shapes(side);
  }
  void add_global_iso_shapes();
  void add_global_explicit_shapes();
  void add_generic_modes(const BlendshapeOptions& o);

  std::vector<DenseShape>& shapes() { return shapes_; }

 private:
  using Change = std::function<void(BodyParams&, double)>;
  using Field = std::function<Vec3(Index)>;

  /// Central-difference iso shape: weight 1 = the parameter moved by +delta.
  void iso(const std::string& name, const Change& change, double lo, double hi) {
    BodyParams plus = P0_, minus = P0_;
    change(plus, 1.0);
    change(minus, -1.0);
    const Points Dp = iso_displacement(tm_, field_, BodyField(plus), N_);
    const Points Dm = iso_displacement(tm_, field_, BodyField(minus), N_);
    shapes_.push_back({name, 0.5 * (Dp - Dm), lo, hi, group_});
  }
  /// A shape from an explicit displacement field.
  void explicit_shape(const std::string& name, const Field& disp, double lo, double hi) {
    Points D(nv_, 3);
    for (Index v = 0; v < nv_; ++v) D.row(v) = disp(v).transpose();
    shapes_.push_back({name, D, lo, hi, group_});
  }
  /// 1 on the side's half of the body (x < 0 for R, x > 0 for L), else 0.
  double on_side(Index v, double s) const { return m_.V(v, 0) * s > 0 ? 1.0 : 0.0; }

  void add_breast_size_shapes(int side);
  void add_breast_shift_shapes(int side);
  void add_breast_contour_shapes(int side);
  void add_nipple_shapes(int side);

  const TemplateMesh& tm_;
  const TriangleMesh& m_;
  const BodyField& field_;
  const model::SkinWeights& W_;
  const Eigen::VectorXd& bh_;  // breast height above the chest wall
  Index nv_;
  Points N_;                   // template_normals
  const BodyParams& P0_;
  std::vector<DenseShape> shapes_;
  int group_ = 0;
};

double side_sign(int side) { return side == 0 ? -1.0 : 1.0; }

/// Volume and projection (iso) and ptosis (sag along the breast's downward axis).
void ShapeBuilder::add_breast_size_shapes(int side) {
  const std::string sfx = side_suffix(side);
  const double s = side_sign(side);
  const BreastFrame fr = field_.breast_frame(side);
  const BreastParams& B = P0_.breast[side];
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
  iso("breast_projection" + sfx, [side](BodyParams& p, double d) { p.breast[side].depth += 14.0 * d; }, -1.0, 1.5);
  explicit_shape("breast_ptosis" + sfx,
                 [&](Index v) -> Vec3 {
                   const Vec3 q = row(m_.V, v) - fr.center;
                   const double w = q.dot(fr.w);
                   const double phi = std::max(0.0, (w - B.sink) / std::max(B.depth - B.sink, 1.0));
                   return -18.0 * std::min(phi * phi, 1.5) * smoothstep(0.0, 6.0, bh_[v]) * on_side(v, s) * fr.v;
                 },
                 -1.2, 2.5);
}

/// Shifts of the whole breast and slides of the skin around it. Wide ranges: supine breasts
/// slide laterally by up to ~50 mm, and a ptotic breast sits well below the template's.
void ShapeBuilder::add_breast_shift_shapes(int side) {
  const std::string sfx = side_suffix(side);
  const double s = side_sign(side);
  const BreastFrame fr = field_.breast_frame(side);
  // Shifts of the whole breast: in proportion to the tissue's height above the chest wall (a
  // supine breast slides laterally by more where it is thicker), so the footprint's border
  // stretches instead of shearing into a crease...
  const double bh_top = std::max(1.0, bh_.maxCoeff());
  auto thickness = [&](Index v) { return std::min(1.0, bh_[v] / (0.6 * bh_top)) * on_side(v, s); };
  explicit_shape("breast_lateral" + sfx, [&](Index v) -> Vec3 { return 15.0 * thickness(v) * Vec3(s, 0, 0); },
                 -1.0, 3.0);
  explicit_shape("breast_cranial" + sfx, [&](Index v) -> Vec3 { return 12.0 * thickness(v) * Vec3::UnitZ(); },
                 -2.5, 2.0);
  // ... and of the skin around it: a wide smooth field along the surface (the skin of the
  // lateral chest wall follows a supine breast towards the axilla).
  auto slide = [&](Index v, const Vec3& dir) -> Vec3 {
    const Vec3 p = row(m_.V, v);
    const double g = std::exp(-(p - fr.base_center).squaredNorm() / (2.0 * 80.0 * 80.0));
    const Vec3 n = row(N_, v);
    return g * smoothstep(0.0, 40.0, s * p.x()) * (dir - dir.dot(n) * n);
  };
  explicit_shape("breast_slide_lateral" + sfx, [&](Index v) -> Vec3 { return 12.0 * slide(v, Vec3(s, 0, 0)); },
                 -1.5, 1.5);
  explicit_shape("breast_slide_cranial" + sfx, [&](Index v) -> Vec3 { return 12.0 * slide(v, Vec3::UnitZ()); },
                 -2.0, 1.5);
}

/// Upper and lower pole fullness, fold height and breast width (iso).
void ShapeBuilder::add_breast_contour_shapes(int side) {
  const std::string sfx = side_suffix(side);
  iso("breast_upper_pole" + sfx, [side](BodyParams& p, double d) { p.breast[side].upper_fullness += 0.2 * d; },
      -1.0, 1.0);
  iso("breast_lower_pole" + sfx, [side](BodyParams& p, double d) { p.breast[side].lower_fullness += 0.2 * d; },
      -1.0, 1.0);
  iso("imf_height" + sfx, [side](BodyParams& p, double d) { p.breast[side].radius_lower -= 10.0 * d; }, -1.0, 1.0);
  iso("breast_width" + sfx, [side](BodyParams& p, double d) { p.breast[side].radius_lateral += 10.0 * d; }, -1.0,
      1.0);
}

/// The nipple moved laterally and up along the surface (a Gaussian on the breast mound).
void ShapeBuilder::add_nipple_shapes(int side) {
  const std::string sfx = side_suffix(side);
  const double s = side_sign(side);
  const BreastFrame fr = field_.breast_frame(side);
  auto mound = [&](Index v) { return smoothstep(0.0, 25.0, bh_[v]) * on_side(v, s); };
  const Vec3 lat_dir = fr.u;
  explicit_shape("nipple_lateral" + sfx,
                 [&](Index v) -> Vec3 {
                   const double r2 = (row(m_.V, v) - fr.nipple).squaredNorm();
                   Vec3 t = lat_dir - lat_dir.dot(row(N_, v)) * row(N_, v);
                   return 8.0 * std::exp(-r2 / (2 * 24.0 * 24.0)) * mound(v) * t;
                 },
                 -2.0, 2.0);
  explicit_shape("nipple_height" + sfx,
                 [&](Index v) -> Vec3 {
                   const double r2 = (row(m_.V, v) - fr.nipple).squaredNorm();
                   Vec3 t = fr.v - fr.v.dot(row(N_, v)) * row(N_, v);
                   return 8.0 * std::exp(-r2 / (2 * 24.0 * 24.0)) * mound(v) * t;
                 },
                 -2.0, 2.0);
}

/// Trunk proportions (global) and arm girth (per side).
void ShapeBuilder::add_global_iso_shapes() {
  group_ = 2;
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
    group_ = side;  // sided shapes are orthogonalised within their side only (mirror symmetry)
    iso(std::string("arm_girth") + side_suffix(side),
        [side](BodyParams& p, double d) {
          auto& a = p.arm[side];
          a.radius_top += 5.0 * d;
          a.radius_mid += 5.0 * d;
          a.deltoid_radius += 4.0 * d;
        },
        -1.0, 1.0);
  }
}

/// Shoulder width and torso length (following the skin weights) and the belly.
void ShapeBuilder::add_global_explicit_shapes() {
  group_ = 2;
  explicit_shape("shoulder_width",
                 [&](Index v) -> Vec3 {
                   const double s = m_.V(v, 0) < 0 ? -1.0 : 1.0;
                   const int c = s < 0 ? kClavicleR : kClavicleL, a = s < 0 ? kUpperArmR : kUpperArmL;
                   return 12.0 * (weight_of(W_, v, c) + weight_of(W_, v, a)) * Vec3(s, 0, 0);
                 },
                 -1.0, 1.0);
  // A belly that protrudes around the umbilicus (abdomen_protrusion moves the whole front of
  // the abdomen, which cannot make a rounded, pointed belly).
  explicit_shape("belly",
                 [&](Index v) -> Vec3 {
                   const Vec3 p = row(m_.V, v);
                   const Vec3 n = row(N_, v);
                   double hw, fy, by, ex;
                   field_.trunk_profile(p.z(), &hw, &fy, &by, &ex);
                   const double front = smoothstep(0.5 * (fy + by), fy + 10.0, p.y());  // anterior half, smoothly
                   const double g = std::exp(-p.x() * p.x() / (2 * 85.0 * 85.0)) *
                                    std::exp(-(p.z() + 330.0) * (p.z() + 330.0) / (2 * 70.0 * 70.0));
                   const double below_folds = smoothstep(-235.0, -285.0, p.z());  // not into the breasts' creases
                   return 15.0 * g * front * below_folds * n;
                 },
                 -1.0, 2.0);
  explicit_shape("torso_length",
                 [&](Index v) -> Vec3 {
                   const double arms = weight_of(W_, v, kUpperArmR) + weight_of(W_, v, kUpperArmL);
                   return -20.0 * smoothstep(-60.0, P0_.waist_cut_z, m_.V(v, 2)) * (1.0 - arms) * Vec3::UnitZ();
                 },
                 -1.0, 1.0);
}

/// Generic smooth modes: normal fields from 5 random Gaussian bumps, mirrored (symmetric for
/// even k, antisymmetric for odd k), scaled to generic_amplitude_mm.
void ShapeBuilder::add_generic_modes(const BlendshapeOptions& o) {
  Rng rng(o.seed);
  for (int k = 0; k < o.generic_modes; ++k) {
    const bool sym = k % 2 == 0;
    std::vector<std::pair<Vec3, double>> bumps;
    for (int b = 0; b < 5; ++b) {
      const Index v = static_cast<Index>(rng.below(static_cast<std::uint64_t>(nv_)));
      bumps.emplace_back(row(m_.V, v), rng.normal());
    }
    auto phi = [&](const Vec3& p) {
      double s = 0;
      for (const auto& [c, a] : bumps)
        s += a * std::exp(-(p - c).squaredNorm() / (2 * o.generic_radius_mm * o.generic_radius_mm));
      return s;
    };
    Eigen::VectorXd val(nv_);
    for (Index v = 0; v < nv_; ++v) {
      const Vec3 p = row(m_.V, v);
      const Vec3 q(-p.x(), p.y(), p.z());
      val[v] = sym ? phi(p) + phi(q) : phi(p) - phi(q);
    }
    const double mx = val.cwiseAbs().maxCoeff();
    if (mx > 1e-12) val *= o.generic_amplitude_mm / mx;
    Points D(nv_, 3);
    for (Index v = 0; v < nv_; ++v) D.row(v) = val[v] * N_.row(v);
    char name[32];
    std::snprintf(name, sizeof name, "generic_%s_%02d", sym ? "sym" : "anti", k / 2);
    shapes_.push_back({name, D, -1.0, 1.0, 3});
  }
}

/// Gram-Schmidt so that the shapes are not redundant: a breast/arm shape against the earlier
/// shapes of its side and a global shape against the earlier global ones when they overlap
/// (|cosine| > 0.25; smaller overlaps are kept so that local shapes stay local), each generic
/// mode against everything before it. Each result is rescaled to the largest displacement it had.
void orthogonalise(std::vector<DenseShape>& shapes) {
  for (size_t i = 0; i < shapes.size(); ++i) {
    DenseShape& si = shapes[i];
    const double max0 = si.D.rowwise().norm().maxCoeff();
    for (size_t j = 0; j < i; ++j) {
      const DenseShape& sj = shapes[j];
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
}

}  // namespace

std::vector<model::Blendshape> template_blendshapes(const TemplateMesh& tm, const BodyField& field,
                                                    const model::SkinWeights& W, const Eigen::VectorXd& bh,
                                                    const BlendshapeOptions& o) {
  if (o.generic_modes < 0) throw InvalidInput("template blendshapes: generic_modes must be >= 0");
  ShapeBuilder builder(tm, field, W, bh);
  for (int side = 0; side < 2; ++side) builder.add_breast_shapes(side);
  builder.add_global_iso_shapes();
  builder.add_global_explicit_shapes();
  builder.add_generic_modes(o);
  std::vector<DenseShape>& shapes = builder.shapes();
  orthogonalise(shapes);
  std::vector<model::Blendshape> out;
  for (const DenseShape& d : shapes) out.push_back(sparse_shape(d.name, d.D, d.lo, d.hi));
  return out;
}

}  // namespace breastfit::templ
