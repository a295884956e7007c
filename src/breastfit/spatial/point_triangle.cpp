#include "breastfit/spatial/point_triangle.h"

#include "breastfit/spatial/detail/point_triangle_kernel.h"

namespace breastfit::spatial {

double closest_point_on_triangle(const double* p, const double* a, const double* b,
                                 const double* c, double* bary, ClosestFeature* feature) {
  ClosestFeature f = ClosestFeature::Face;
  const double s = detail::closest_point_on_triangle_kernel(
      p, a, b, c, detail::is_degenerate_triangle(a, b, c), bary, f);
  if (feature != nullptr) *feature = f;
  return s;
}

PointTriangleResult closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                              const Vec3& c) {
  PointTriangleResult r;
  r.sq_dist = closest_point_on_triangle(p.data(), a.data(), b.data(), c.data(), r.bary.data(),
                                        &r.feature);
  r.point = r.bary[0] * a + r.bary[1] * b + r.bary[2] * c;
  return r;
}

bool is_vertex_feature(ClosestFeature feature) {
  return feature == ClosestFeature::Vertex0 || feature == ClosestFeature::Vertex1 ||
         feature == ClosestFeature::Vertex2;
}

bool is_edge_feature(ClosestFeature feature) {
  return feature == ClosestFeature::Edge01 || feature == ClosestFeature::Edge12 ||
         feature == ClosestFeature::Edge20;
}

}  // namespace breastfit::spatial
