#include "breastfit/render/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "breastfit/core/errors.h"

namespace breastfit::render {

namespace {
constexpr double kPi = 3.14159265358979323846;

bool finite(const Vec3& v) { return v.allFinite(); }
}  // namespace

Vec3 Camera::forward() const { return (target - eye).normalized(); }
Vec3 Camera::right() const { return forward().cross(up).normalized(); }
Vec3 Camera::true_up() const { return right().cross(forward()); }

namespace {

/// Camera::project with the camera's axes and scales computed once.
struct Projector {
  Vec3 eye, f, r, u;
  bool orthographic = true;
  double half_h = 1, aspect = 1, t = 1, near = 0;
  int width = 1, height = 1;

  Projector(const Camera& c, int w, int h)
      : eye(c.eye), f(c.forward()), orthographic(c.projection == Projection::Orthographic), near(c.near),
        width(w), height(h) {
    r = f.cross(c.up).normalized();
    u = r.cross(f);
    aspect = static_cast<double>(width) / height;
    half_h = 0.5 * c.view_height;
    t = std::tan(0.5 * c.fov_y_deg * kPi / 180.0);
  }

  Projected operator()(const Vec3& p) const {
    const Vec3 d = p - eye;
    const double xc = d.dot(r), yc = d.dot(u), zc = d.dot(f);
    double nx = 0, ny = 0;
    if (orthographic) {
      nx = xc / (half_h * aspect);
      ny = yc / half_h;
    } else {
      const double z = std::max(zc, near);
      nx = xc / (z * t * aspect);
      ny = yc / (z * t);
    }
    return {0.5 * (nx + 1.0) * width, 0.5 * (1.0 - ny) * height, zc};
  }
};

}  // namespace

Projected Camera::project(const Vec3& p, int width, int height) const { return Projector(*this, width, height)(p); }

std::vector<Projected> Camera::project_all(const Points& points, int width, int height) const {
  const Projector project(*this, width, height);
  std::vector<Projected> out(static_cast<size_t>(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i) out[static_cast<size_t>(i)] = project(points.row(i).transpose());
  return out;
}

double Camera::world_per_pixel(double depth, int height) const {
  if (projection == Projection::Orthographic) return view_height / height;
  const double t = std::tan(0.5 * fov_y_deg * kPi / 180.0);
  return 2.0 * std::max(depth, near) * t / height;
}

void Camera::validate() const {
  if (!finite(eye) || !finite(target) || !finite(up))
    throw InvalidInput("Camera: eye, target and up must be finite");
  const Vec3 d = target - eye;
  if (d.norm() <= 0) throw InvalidInput("Camera: eye and target coincide");
  if (up.norm() <= 0 || d.normalized().cross(up.normalized()).norm() < 1e-9)
    throw InvalidInput("Camera: up is zero or parallel to the viewing direction");
  if (projection == Projection::Orthographic && !(view_height > 0 && std::isfinite(view_height)))
    throw InvalidInput("Camera: view_height must be positive, got " + std::to_string(view_height));
  if (projection == Projection::Perspective &&
      !(fov_y_deg > 0 && fov_y_deg < 179 && near > 0 && std::isfinite(near)))
    throw InvalidInput("Camera: fov_y_deg must be in (0, 179) and near > 0");
}

Camera frame_points(const Points& points, const Vec3& view_dir, const Vec3& up, double aspect,
                    double margin, Projection projection, double fov_y_deg) {
  if (points.rows() == 0) throw InvalidInput("frame_points: no points to frame");
  if (!points.allFinite()) throw InvalidInput("frame_points: points must be finite");
  if (!(aspect > 0) || !(margin >= 0 && margin < 0.5))
    throw InvalidInput("frame_points: aspect must be > 0 and margin in [0, 0.5)");
  if (view_dir.norm() <= 0 || up.norm() <= 0 || view_dir.normalized().cross(up.normalized()).norm() < 1e-9)
    throw InvalidInput("frame_points: view_dir and up must be non-zero and not parallel");
  const Vec3 f = view_dir.normalized();
  const Vec3 r = f.cross(up).normalized();
  const Vec3 u = r.cross(f);
  // Extent in the camera's plane and along the view.
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  double y_lo = x_lo, y_hi = -x_lo, z_lo = x_lo, z_hi = -x_lo;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Vec3 p = points.row(i).transpose();
    x_lo = std::min(x_lo, p.dot(r));
    x_hi = std::max(x_hi, p.dot(r));
    y_lo = std::min(y_lo, p.dot(u));
    y_hi = std::max(y_hi, p.dot(u));
    z_lo = std::min(z_lo, p.dot(f));
    z_hi = std::max(z_hi, p.dot(f));
  }
  const double fill = 1.0 - 2.0 * margin;
  double half_w = 0.5 * (x_hi - x_lo), half_h = 0.5 * (y_hi - y_lo);
  const double scene_size = std::max({x_hi - x_lo, y_hi - y_lo, z_hi - z_lo, 1e-9});
  half_w = std::max(half_w, 1e-6 * scene_size);
  half_h = std::max(half_h, 1e-6 * scene_size);
  const double view_height = std::max(2.0 * half_h, 2.0 * half_w / aspect) / fill;
  const Vec3 centre = r * (0.5 * (x_lo + x_hi)) + u * (0.5 * (y_lo + y_hi)) + f * (0.5 * (z_lo + z_hi));

  Camera cam;
  cam.up = u;
  cam.projection = projection;
  cam.fov_y_deg = fov_y_deg;
  cam.view_height = view_height;
  if (projection == Projection::Orthographic) {
    // Eye in front of the nearest point; depth values stay positive.
    const double back = 0.5 * (z_hi - z_lo) + scene_size;
    cam.target = centre;
    cam.eye = centre - f * back;
    return cam;
  }
  // Perspective: smallest distance (from the near face of the extent) such that every point fits.
  const double t = std::tan(0.5 * fov_y_deg * kPi / 180.0);
  const double cx = 0.5 * (x_lo + x_hi), cy = 0.5 * (y_lo + y_hi);
  double eye_z = z_lo - 1e-6 * scene_size;  // eye position along f (camera plane coordinate)
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Vec3 p = points.row(i).transpose();
    const double dx = std::abs(p.dot(r) - cx), dy = std::abs(p.dot(u) - cy);
    const double need = std::max(dx / (t * aspect * fill), dy / (t * fill));
    eye_z = std::min(eye_z, p.dot(f) - need);
  }
  cam.eye = r * cx + u * cy + f * eye_z;
  cam.target = r * cx + u * cy + f * (0.5 * (z_lo + z_hi));
  cam.near = 1e-3 * scene_size;
  return cam;
}

Camera frame_box(const Eigen::AlignedBox3d& box, const Vec3& view_dir, const Vec3& up, double aspect,
                 double margin, Projection projection, double fov_y_deg) {
  if (box.isEmpty()) throw InvalidInput("frame_box: the box is empty");
  Points corners(8, 3);
  for (int i = 0; i < 8; ++i)
    corners.row(i) = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)).transpose();
  return frame_points(corners, view_dir, up, aspect, margin, projection, fov_y_deg);
}

}  // namespace breastfit::render
