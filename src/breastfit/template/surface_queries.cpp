#include "breastfit/template/surface_queries.h"

#include <limits>

#include "breastfit/core/errors.h"

namespace breastfit::templ {

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3* bary) {
  // Ericson, Real-Time Collision Detection, 5.1.5.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) { *bary = Vec3(1, 0, 0); return a; }
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) { *bary = Vec3(0, 1, 0); return b; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    *bary = Vec3(1 - v, v, 0);
    return a + v * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) { *bary = Vec3(0, 0, 1); return c; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    *bary = Vec3(1 - w, 0, w);
    return a + w * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    *bary = Vec3(0, 1 - w, w);
    return b + w * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  *bary = Vec3(1 - v - w, v, w);
  return a + ab * v + ac * w;
}

SurfacePoint closest_surface_point(const TriangleMesh& mesh, const Vec3& q) {
  if (mesh.num_faces() == 0) throw InvalidInput("closest_surface_point: mesh has no triangles");
  SurfacePoint best;
  double best_d = std::numeric_limits<double>::infinity();
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    Vec3 bary;
    const Vec3 p = closest_point_on_triangle(q, mesh.V.row(mesh.F(f, 0)).transpose(),
                                             mesh.V.row(mesh.F(f, 1)).transpose(),
                                             mesh.V.row(mesh.F(f, 2)).transpose(), &bary);
    const double d = (p - q).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best.face = f;
      best.bary = bary;
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
