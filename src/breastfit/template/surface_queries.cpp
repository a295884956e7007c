#include "breastfit/template/surface_queries.h"

#include <limits>

#include "breastfit/core/errors.h"
#include "breastfit/spatial/point_triangle.h"

namespace breastfit::templ {

SurfacePoint closest_surface_point(const TriangleMesh& mesh, const Vec3& q) {
  if (mesh.num_faces() == 0) throw InvalidInput("closest_surface_point: mesh has no triangles");
  SurfacePoint best;
  double best_d = std::numeric_limits<double>::infinity();
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const spatial::PointTriangleResult r = spatial::closest_point_on_triangle(
        q, mesh.V.row(mesh.F(f, 0)).transpose(), mesh.V.row(mesh.F(f, 1)).transpose(),
        mesh.V.row(mesh.F(f, 2)).transpose());
    if (r.sq_dist < best_d) {
      best_d = r.sq_dist;
      best.face = f;
      best.bary = r.bary;
    }
  }
  return best;
}

std::optional<SurfacePoint> first_ray_hit(const TriangleMesh& mesh, const Vec3& o, const Vec3& dir,
                                          double max_t) {
  std::optional<SurfacePoint> best;
  double best_t = max_t;
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 a = mesh.V.row(mesh.F(f, 0)).transpose();
    const Vec3 e1 = mesh.V.row(mesh.F(f, 1)).transpose() - a;
    const Vec3 e2 = mesh.V.row(mesh.F(f, 2)).transpose() - a;
    const Vec3 pv = dir.cross(e2);
    const double det = e1.dot(pv);
    if (std::abs(det) < 1e-14) continue;
    const double inv = 1.0 / det;
    const Vec3 tv = o - a;
    const double u = tv.dot(pv) * inv;
    if (u < 0 || u > 1) continue;
    const Vec3 qv = tv.cross(e1);
    const double v = dir.dot(qv) * inv;
    if (v < 0 || u + v > 1) continue;
    const double t = e2.dot(qv) * inv;
    if (t <= 0 || t > best_t) continue;
    best_t = t;
    SurfacePoint sp;
    sp.face = f;
    sp.bary = Vec3(1 - u - v, u, v);
    best = sp;
  }
  return best;
}

}  // namespace breastfit::templ
