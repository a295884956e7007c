#include "breastfit/transfer/drawing_transfer.h"

#include <cmath>
#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/body_frame.h"
#include "breastfit/spatial/ray_caster.h"
#include "breastfit/transfer/polyline.h"

namespace breastfit::transfer {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool all_finite(const Points& P) { return P.allFinite(); }

}  // namespace

void TransferOptions::validate() const {
  auto fail = [](const std::string& field, double v, const std::string& rule) {
    throw InvalidInput("TransferOptions." + field + " = " + std::to_string(v) + ": " + rule);
  };
  if (!(max_distance_mm > 0) || !std::isfinite(max_distance_mm)) fail("max_distance_mm", max_distance_mm, "must be > 0");
  if (!(max_normal_angle_deg > 0 && max_normal_angle_deg <= 90))
    fail("max_normal_angle_deg", max_normal_angle_deg, "must be in (0, 90]");
  if (!(spacing_mm > 0) || !std::isfinite(spacing_mm)) fail("spacing_mm", spacing_mm, "must be > 0");
  if (smoothing_passes < 0) fail("smoothing_passes", smoothing_passes, "must be >= 0");
  if (!(smoothing_weight >= 0 && smoothing_weight <= 1)) fail("smoothing_weight", smoothing_weight, "must be in [0, 1]");
  if (!(fold_facing_down_cos > 0 && fold_facing_down_cos <= 1))
    fail("fold_facing_down_cos", fold_facing_down_cos, "must be in (0, 1]");
  if (!(fold_max_slide_mm >= 0) || !std::isfinite(fold_max_slide_mm)) fail("fold_max_slide_mm", fold_max_slide_mm, "must be >= 0");
}

struct DrawingTransfer::Rays {
  spatial::RayCaster caster;
  explicit Rays(const TriangleMesh& m) : caster(m) {}
};

struct DrawingTransfer::Projection {
  bool supported = false;
  Vec3 point = Vec3::Zero();
};

DrawingTransfer::DrawingTransfer(const fit::ScanTarget& scan, const TriangleMesh& fitted_mm, const TransferOptions& options)
    : scan_(scan), fitted_((options.validate(), fitted_mm)), options_(options) {
  if (options_.mode == ProjectionMode::AlongNormal) rays_ = std::make_unique<Rays>(scan_.mesh());
}

DrawingTransfer::~DrawingTransfer() = default;

DrawingTransfer::Projection DrawingTransfer::project(const Vec3& m, const Vec3& n, Index* scan_face) const {
  Projection out;
  const double cos_max = std::cos(options_.max_normal_angle_deg * kPi / 180.0);
  if (options_.mode == ProjectionMode::ClosestPoint) {
    const auto match = scan_.match(m, options_.max_distance_mm, scan_face);
    if (!match || (options_.reject_scan_border && match->on_boundary)) return out;
    if (n.squaredNorm() > 0 && std::abs(n.dot(match->normal)) < cos_max) return out;
    out.supported = true;
    out.point = match->point;
    return out;
  }
  if (n.squaredNorm() == 0) return out;
  const auto up = rays_->caster.intersect(m, n, options_.max_distance_mm);
  const auto down = rays_->caster.intersect(m, -n, options_.max_distance_mm);
  const spatial::RayHit* hit = nullptr;
  if (up && (!down || up->t <= down->t)) hit = &*up;
  else if (down) hit = &*down;
  if (!hit) return out;
  // A hit on a triangle touching the open border is the rim of a hole or of the scanned area.
  const fit::ScanMatch at = scan_.closest(hit->point);
  if (options_.reject_scan_border && at.on_boundary) return out;
  if (std::abs(n.dot(at.normal)) < cos_max) return out;
  out.supported = true;
  out.point = hit->point;
  return out;
}

DrawingTransfer::PointProjection DrawingTransfer::project_point(const Vec3& q) const {
  if (!q.allFinite()) throw InvalidInput("project_point: non-finite point");
  const auto cp = fitted_.closest(q);
  PointProjection out;
  out.model_point = cp.point;
  const Projection p = project(cp.point, fitted_.smooth_normal(cp));
  out.supported = p.supported;
  out.point = p.supported ? p.point : cp.point;
  out.model_to_scan_mm = p.supported ? (p.point - cp.point).norm() : 0.0;
  return out;
}

void DrawingTransfer::set_body_axes(const Vec3& superior, const Vec3& anterior) {
  if (!superior.allFinite() || !anterior.allFinite() || std::abs(superior.norm() - 1) > 1e-6 ||
      std::abs(anterior.norm() - 1) > 1e-6 || std::abs(superior.dot(anterior)) > 1e-6)
    throw InvalidInput("set_body_axes: superior and anterior must be orthogonal unit vectors");
  body_axes_ = std::make_pair(superior, anterior);
}

Vec3 DrawingTransfer::slide_into_fold(const Vec3& q) const { return slide(q, -1).point; }

spatial::ClosestPoint DrawingTransfer::slide(const Vec3& q, Index hint_face) const {
  auto cp = fitted_.closest(q, hint_face);
  if (!body_axes_ || options_.fold_facing_down_cos >= 1) return cp;
  const auto& [superior, anterior] = *body_axes_;
  constexpr double kStep = 1.0;  // mm along the surface per step
  for (double walked = 0; walked + kStep <= options_.fold_max_slide_mm; walked += kStep) {
    const Vec3 n = fitted_.smooth_normal(cp);
    if (-n.dot(superior) <= options_.fold_facing_down_cos) break;  // not (or no longer) under an overhang
    const Vec3 back = -anterior - (-anterior).dot(n) * n;          // posterior, in the tangent plane
    if (back.norm() < 1e-6) break;
    cp = fitted_.closest(Vec3(cp.point + kStep * back.normalized()), cp.face);
  }
  return cp;
}

TransferredCurve DrawingTransfer::transfer(const std::string& name, bool closed, const Points& model_points_mm) const {
  if (model_points_mm.rows() == 0) throw InvalidInput("transfer: drawing '" + name + "' has no points");
  if (!all_finite(model_points_mm)) throw InvalidInput("transfer: drawing '" + name + "' has non-finite points");
  TransferredCurve c;
  c.name = name;
  c.closed = closed;

  // Every closest-point query below is warm-started (the same result, only faster): from the
  // previous point's face along the curve (~spacing_mm away), then from the point's own face of
  // the pass before. model_face: on the fitted surface; scan_face: on the scan (-1 = none yet).
  // 1. Resample on the fitted surface.
  Points model = resample_polyline(model_points_mm, closed, options_.spacing_mm);
  const Eigen::Index n = model.rows();
  Points normals(n, 3);
  std::vector<Index> model_face(static_cast<size_t>(n), -1);
  std::vector<Index> scan_face(static_cast<size_t>(n), -1);
  Index hint = -1;
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto slid = slide(model.row(i).transpose(), hint);
    const auto cp = fitted_.closest(slid.point, slid.face);
    model.row(i) = cp.point.transpose();
    normals.row(i) = fitted_.smooth_normal(cp).transpose();
    hint = model_face[static_cast<size_t>(i)] = cp.face;
  }

  // 2. Project onto the scan where it supports the curve.
  c.points = model;
  c.supported.assign(static_cast<size_t>(n), false);
  double sum = 0;
  Eigen::Index count = 0;
  Index scan_hint = -1;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Projection p = project(model.row(i).transpose(), normals.row(i).transpose(), &scan_hint);
    scan_face[static_cast<size_t>(i)] = scan_hint;
    if (!p.supported) continue;
    c.supported[static_cast<size_t>(i)] = true;
    c.points.row(i) = p.point.transpose();
    sum += (p.point - model.row(i).transpose()).norm();
    ++count;
  }
  c.supported_fraction = static_cast<double>(count) / static_cast<double>(n);
  c.mean_model_to_scan_mm = count > 0 ? sum / static_cast<double>(count) : 0.0;

  // 3. Light smoothing, each pass followed by re-projection onto the surface the point belongs to.
  for (int pass = 0; pass < options_.smoothing_passes; ++pass) {
    c.points = laplacian_smooth(c.points, closed, options_.smoothing_weight);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Vec3 q = c.points.row(i).transpose();
      const auto k = static_cast<size_t>(i);
      if (c.supported[k]) {
        c.points.row(i) = scan_.closest(q, &scan_face[k]).point.transpose();
      } else {
        const auto cp = fitted_.closest(q, model_face[k]);
        model_face[k] = cp.face;
        c.points.row(i) = cp.point.transpose();
      }
    }
  }
  c.length_mm = polyline_length(c.points, closed);
  return c;
}

std::vector<TransferredCurve> transfer_drawings(const model::RiggedModel& model, const Points& posed_mm,
                                                const fit::ScanTarget& scan, const TransferOptions& options) {
  if (posed_mm.rows() != model.num_vertices())
    throw InvalidInput("transfer_drawings: " + std::to_string(posed_mm.rows()) + " posed vertices for a model with " +
                       std::to_string(model.num_vertices()));
  TriangleMesh fitted;
  fitted.V = posed_mm;
  fitted.F = model.rest.F;
  DrawingTransfer transfer(scan, fitted, options);
  // Body axes from the fitted landmarks (for the fold slide); without them no slide.
  mesh::NamedPositions lms;
  for (const auto& l : model.landmarks) lms[l.name] = l.point.position(posed_mm, model.rest.F);
  if (const auto frame = mesh::body_frame_from_landmarks(lms)) {
    const Mat3 R = frame->body_to_world.topLeftCorner<3, 3>();
    transfer.set_body_axes(R.col(2).normalized(), -R.col(1).normalized());  // LPS: +z superior, −y anterior
  }
  std::vector<TransferredCurve> out;
  for (const auto& d : model.drawings) {
    Points P(static_cast<Eigen::Index>(d.points.size()), 3);
    for (size_t i = 0; i < d.points.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = d.points[i].position(posed_mm, model.rest.F).transpose();
    out.push_back(transfer.transfer(d.name, d.closed, P));
  }
  return out;
}

Markups to_markups(const std::vector<TransferredCurve>& curves) {
  Markups m;
  for (const auto& c : curves) m.curves.push_back(Curve{c.name, c.closed, c.points});
  return m;
}

}  // namespace breastfit::transfer
