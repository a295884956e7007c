#include "breastfit/template/template_annotations.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/landmark_names.h"
#include "breastfit/template/surface_paths.h"
#include "breastfit/template/surface_queries.h"
#include "breastfit/template/template_skeleton.h"

namespace breastfit::templ {
namespace {

Vec3 vpos(const TriangleMesh& m, Index v) { return m.V.row(v).transpose(); }

/// The anterior midline: seam vertices (x = 0) in front of the trunk centre, top to bottom.
std::vector<Index> front_seam(const TemplateMesh& tm, const BodyField& field) {
  const TriangleMesh& m = tm.mesh;
  std::vector<std::pair<double, Index>> s;
  for (Index v = 0; v < m.num_vertices(); ++v) {
    if (tm.mirror[v] != v) continue;
    const Vec3 p = vpos(m, v);
    double w, f, b, n;
    field.trunk_profile(p.z(), &w, &f, &b, &n);
    const double ymid = p.z() > 0 ? field.params().neck_center_y : 0.5 * (f + b);
    if (p.y() < ymid) s.emplace_back(-p.z(), v);
  }
  std::sort(s.begin(), s.end());
  std::vector<Index> out;
  for (const auto& e : s) out.push_back(e.second);
  return out;
}

/// The part of an open path between heights z_top and z_bottom (path runs downwards).
SurfacePath clip_path_z(const TriangleMesh& m, const SurfacePath& path, double z_top, double z_bot) {
  SurfacePath out;
  for (const auto& s : path.segments) {
    const double z0 = segment_point(m, s, 0).z(), z1 = segment_point(m, s, 1).z();
    if (std::max(z0, z1) < z_bot || std::min(z0, z1) > z_top) continue;
    double t0 = 0, t1 = 1;
    if (z0 != z1) {
      const double ta = (z_top - z0) / (z1 - z0), tb = (z_bot - z0) / (z1 - z0);
      t0 = std::clamp(std::min(ta, tb), 0.0, 1.0);
      t1 = std::clamp(std::max(ta, tb), 0.0, 1.0);
    }
    if (t1 - t0 < 1e-9) continue;
    PathSegment c = s;
    c.bary0 = (1 - t0) * s.bary0 + t0 * s.bary1;
    c.bary1 = (1 - t1) * s.bary0 + t1 * s.bary1;
    out.segments.push_back(c);
  }
  return out;
}

SurfacePoint start_of(const PathSegment& s) {
  SurfacePoint p;
  p.face = s.face;
  p.bary = s.bary0;
  return p;
}
SurfacePoint end_of(const PathSegment& s) {
  SurfacePoint p;
  p.face = s.face;
  p.bary = s.bary1;
  return p;
}

SurfacePoint ray_landmark(const TriangleMesh& m, const Vec3& o, const Vec3& d, const char* name) {
  const auto hit = first_ray_hit(m, o, d.normalized(), 1000.0);
  if (!hit) throw InvalidInput(std::string("template: cannot place landmark ") + name);
  return *hit;
}

SurfacePoint vertex_point(const TriangleMesh& m, Index v) {
  for (Index f = 0; f < m.num_faces(); ++f)
    for (int c = 0; c < 3; ++c)
      if (m.F(f, c) == v) {
        SurfacePoint sp;
        sp.face = f;
        sp.bary = Vec3::Zero();
        sp.bary[c] = 1.0;
        return sp;
      }
  throw InvalidInput("template: isolated vertex");
}

/// A closed curve on the mesh: Gaussian-smoothed (sigma along arc length, mm) polyline through
/// P (~1 mm spacing), resampled every `spacing` mm and snapped onto the mesh.
std::vector<SurfacePoint> smooth_closed_curve(const TriangleMesh& m, const std::vector<Vec3>& P, double sigma,
                                              double spacing) {
  const int n = static_cast<int>(P.size());
  double total = 0;
  for (int i = 0; i < n; ++i) total += (P[(i + 1) % n] - P[i]).norm();
  const double h = total / n;  // mean spacing
  const int half = static_cast<int>(std::ceil(3 * sigma / h));
  std::vector<Vec3> S(n);
  for (int i = 0; i < n; ++i) {
    Vec3 acc = Vec3::Zero();
    double wsum = 0;
    for (int k = -half; k <= half; ++k) {
      const double w = std::exp(-0.5 * (k * h / sigma) * (k * h / sigma));
      acc += w * P[((i + k) % n + n) % n];
      wsum += w;
    }
    S[i] = acc / wsum;
  }
  for (auto& p : S) p = closest_surface_point(m, p).position(m.V, m.F);
  // Resample by arc length.
  std::vector<double> cum(n + 1, 0.0);
  for (int i = 0; i < n; ++i) cum[i + 1] = cum[i] + (S[(i + 1) % n] - S[i]).norm();
  const int count = std::max(3, static_cast<int>(std::lround(cum[n] / spacing)));
  std::vector<SurfacePoint> out;
  int seg = 0;
  for (int k = 0; k < count; ++k) {
    const double t = cum[n] * k / count;
    while (seg + 1 < n && cum[seg + 1] < t) ++seg;
    const double len = cum[seg + 1] - cum[seg];
    const double a = len > 1e-12 ? (t - cum[seg]) / len : 0.0;
    const Vec3 q = (1 - a) * S[seg] + a * S[(seg + 1) % n];
    out.push_back(closest_surface_point(m, q));
  }
  return out;
}

// Moves a surface point `distance` mm down the surface (along −z projected onto the tangent
// plane), in 1 mm steps each re-projected onto the surface.
Vec3 walk_down(const TriangleMesh& m, Vec3 p, double distance) {
  const int steps = static_cast<int>(std::ceil(distance));
  for (int k = 0; k < steps; ++k) {
    const SurfacePoint sp = closest_surface_point(m, p);
    const Vec3 a = m.V.row(m.F(sp.face, 0)).transpose(), b = m.V.row(m.F(sp.face, 1)).transpose(),
               c = m.V.row(m.F(sp.face, 2)).transpose();
    const Vec3 n = (b - a).cross(c - a).normalized();
    Vec3 t = -Vec3::UnitZ() + n.z() * n;
    if (t.norm() < 1e-6) break;  // a horizontal face: no downhill direction
    p = closest_surface_point(m, sp.position(m.V, m.F) + (distance / steps) * t.normalized()).position(m.V, m.F);
  }
  return p;
}

}  // namespace

TemplateAnnotations template_annotations(const TemplateMesh& tm, const BodyField& field,
                                         const Eigen::VectorXd& bh, const model::SkinWeights& W,
                                         const AnnotationOptions& o) {
  const TriangleMesh& m = tm.mesh;
  TemplateAnnotations out;
  std::vector<SurfacePoint> lm(kLandmarkNames.size());

  // Midline: sternal notch (z = 0) and xiphoid on the anterior seam.
  const SurfacePath seam = edge_path(m, front_seam(tm, field));
  const SurfacePath sternum = clip_path_z(m, seam, 0.0, o.xiphoid_z);
  if (sternum.segments.empty()) throw InvalidInput("template: no anterior midline");
  lm[0] = start_of(sternum.segments.front());
  lm[1] = end_of(sternum.segments.back());

  // Breast contours: the footprint is where the skin lies within footprint_margin_mm of the
  // breast's own ellipsoid (the gland), so the long gentle blend of the upper pole into the
  // chest wall is not counted as breast (with a skin-height threshold the contour sat ~15 mm
  // too high and too far towards the axilla).
  Eigen::VectorXd gland(m.num_vertices());
  for (Index v = 0; v < m.num_vertices(); ++v)
    gland[v] = -field.breast_value(m.V.row(v).transpose(), m.V(v, 0) < 0 ? 0 : 1);
  const double fp_level = -o.footprint_margin_mm;
  std::array<std::vector<SurfacePoint>, 2> contour;
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? -1.0 : 1.0;
    auto lines = iso_lines(m, gland, fp_level);
    const SurfacePath* best = nullptr;
    double best_len = 0;
    for (const auto& l : lines) {
      if (!l.closed) continue;
      const Vec3 c = segment_point(m, l.segments.front(), 0);
      if (c.x() * s <= 0) continue;
      const double len = path_length(m, l);
      if (len > best_len) {
        best_len = len;
        best = &l;
      }
    }
    if (!best) throw InvalidInput("template: no breast footprint");
    SurfacePath loop = *best;
    double area = 0;
    for (const auto& sg : loop.segments) {
      const Vec3 a = segment_point(m, sg, 0), b = segment_point(m, sg, 1);
      area += a.x() * b.z() - b.x() * a.z();
    }
    if (area < 0) loop = reversed(loop);
    Vec3 top = segment_point(m, loop.segments.front(), 0);
    for (const auto& sg : loop.segments) {
      const Vec3 a = segment_point(m, sg, 0);
      if (a.z() > top.z()) top = a;
    }
    loop = rotated_to_start_near(m, loop, top);
    std::vector<Vec3> fine;
    for (const auto& sp : resample_path(m, loop, 1.0)) fine.push_back(sp.position(m.V, m.F));
    double zlo = fine.front().z(), zhi = zlo;
    for (const Vec3& p : fine) zlo = std::min(zlo, p.z()), zhi = std::max(zhi, p.z());
    const double zmid = 0.5 * (zlo + zhi);
    for (Vec3& p : fine)
      if (p.z() > zmid && zhi > zmid) {
        const double u = (p.z() - zmid) / (zhi - zmid);
        p = walk_down(m, p, o.contour_top_lowering_mm * u);  // linear: the top stays rounded
      }
    auto pts = smooth_closed_curve(m, fine, o.contour_smoothing_mm, o.drawing_spacing_mm);
    // Start at the most superior point.
    size_t top_i = 0;
    for (size_t i = 0; i < pts.size(); ++i)
      if (pts[i].position(m.V, m.F).z() > pts[top_i].position(m.V, m.F).z()) top_i = i;
    std::rotate(pts.begin(), pts.begin() + static_cast<std::ptrdiff_t>(top_i), pts.end());
    contour[side] = std::move(pts);
  }

  // Lowest breast point: min z over the breast mound; folds: the lower part of the contour.
  std::array<std::vector<SurfacePoint>, 2> imf;
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? -1.0 : 1.0;
    const auto& c = contour[side];
    const size_t n = c.size();
    std::vector<Vec3> P(n);
    for (size_t i = 0; i < n; ++i) P[i] = c[i].position(m.V, m.F);
    size_t lo = 0, med = 0, lat = 0;
    for (size_t i = 0; i < n; ++i) {
      if (P[i].z() < P[lo].z()) lo = i;
      if (std::abs(P[i].x()) < std::abs(P[med].x())) med = i;
      if (std::abs(P[i].x()) > std::abs(P[lat].x())) lat = i;
    }
    // Over the mound (skin lifted by the breast) including its border, which reaches lower
    // than the gland contour.
    SurfacePoint lowest = c[lo];
    double zmin = std::numeric_limits<double>::infinity();
    for (const auto& line : iso_lines(m, bh, o.footprint_height_mm))
      for (const auto& sg : line.segments) {
        const Vec3 a = segment_point(m, sg, 0);
        if (a.x() * s > 0 && a.z() < zmin) {
          zmin = a.z();
          lowest = start_of(sg);
        }
      }
    for (Index v = 0; v < m.num_vertices(); ++v) {
      if (bh[v] < o.footprint_height_mm || m.V(v, 0) * s <= 0) continue;
      if (m.V(v, 2) < zmin) {
        zmin = m.V(v, 2);
        lowest = vertex_point(m, v);
      }
    }
    lm[10 + side] = lowest;
    // IMF: from the medial-most to the lateral-most point through the lowest one.
    bool forward = false;
    for (size_t k = 0, i = med; k < n; ++k, i = (i + 1) % n) {
      if (i == lo) { forward = true; break; }
      if (i == lat) break;
    }
    for (size_t k = 0, i = med; k < n; ++k) {
      imf[side].push_back(c[i]);
      if (i == lat) break;
      i = forward ? (i + 1) % n : (i + n - 1) % n;
    }
  }

  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? -1.0 : 1.0;
    const Vec3& J = field.shoulder_joint(side);
    const Vec3& d = field.humerus_dir(side);
    const BreastFrame& fr = field.breast_frame(side);
    // Acromion: the top of the shoulder above the acromio-clavicular joint.
    const Vec3 ac = acromion_point(field, side);
    lm[2 + side] = ray_landmark(m, ac + Vec3(0, 0, 200), -Vec3::UnitZ(), "acromion");
    // Mid-axillary: lateral chest wall in the coronal plane of the shoulder joint, nipple level.
    lm[4 + side] = ray_landmark(m, Vec3(0, J.y(), fr.nipple.z() + 20.0), Vec3(s, 0, 0), "midaxillary");
    // Pectoral insertion: anterior-medial surface of the upper arm at the axillary fold.
    Vec3 am(-s * 0.45, -0.9, 0.0);
    am -= am.dot(d) * d;
    lm[6 + side] = ray_landmark(m, J + 68.0 * d, am, "pectoral_insertion");
    // Nipple: the apex material point.
    lm[8 + side] = closest_surface_point(m, fr.nipple);
  }
  for (size_t i = 0; i < kLandmarkNames.size(); ++i)
    out.landmarks.push_back({std::string(kLandmarkNames[i]), lm[i]});

  auto drawing = [](std::string name, bool closed, std::vector<SurfacePoint> pts) {
    model::Drawing d;
    d.name = std::move(name);
    d.closed = closed;
    d.points = std::move(pts);
    return d;
  };
  out.drawings.push_back(drawing("breast_contour_R", true, contour[0]));
  out.drawings.push_back(drawing("breast_contour_L", true, contour[1]));
  out.drawings.push_back(drawing("sternum", false, resample_path(m, sternum, o.drawing_spacing_mm)));
  out.drawings.push_back(drawing("imf_R", false, imf[0]));
  out.drawings.push_back(drawing("imf_L", false, imf[1]));

  // Regions.
  const char* names[] = {"abdomen", "thorax", "neck", "shoulder_R", "shoulder_L", "arm_R", "arm_L"};
  std::vector<model::VertexRegion> regions(2 + 7);
  regions[0].name = "breast_R";
  regions[1].name = "breast_L";
  for (int k = 0; k < 7; ++k) regions[2 + k].name = names[k];
  for (Index v = 0; v < m.num_vertices(); ++v) {
    if (bh[v] >= o.footprint_height_mm) {
      regions[m.V(v, 0) < 0 ? 0 : 1].vertices.push_back(v);
      continue;
    }
    int best = 0;
    double bw = -1;
    for (model::SkinWeights::InnerIterator it(W, v); it; ++it) {
      if (it.col() < kBreastR && it.value() > bw) {
        bw = it.value();
        best = static_cast<int>(it.col());
      }
    }
    if (bw > 0) regions[2 + best].vertices.push_back(v);
  }
  out.regions = std::move(regions);
  return out;
}

}  // namespace breastfit::templ
