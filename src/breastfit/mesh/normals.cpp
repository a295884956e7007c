#include "breastfit/mesh/normals.h"

#include <cmath>

#include "breastfit/mesh/triangle_indices.h"

namespace breastfit::mesh {
namespace {

void check_indices(const Points& V, const Triangles& F) {
  check_triangle_indices(F, static_cast<Index>(V.rows()));
}

/// The normalisation rule of the file comment: x / |x|, or zero when |x| is 0 or not finite.
template <class Vector>
void normalise_or_zero(Vector&& x) {
  const double len = x.norm();
  if (len > 0.0 && std::isfinite(len)) {
    x /= len;
  } else {
    x.setZero();
  }
}

Vec3 cross_of(const Points& V, const Triangles& F, Eigen::Index f) {
  const Vec3 a = V.row(F(f, 0)).transpose();
  const Vec3 b = V.row(F(f, 1)).transpose();
  const Vec3 c = V.row(F(f, 2)).transpose();
  return (b - a).cross(c - a);
}

}  // namespace

Points face_normals(const Points& V, const Triangles& F) {
  check_indices(V, F);
  Points N(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    Vec3 n = cross_of(V, F, f);
    normalise_or_zero(n);
    N.row(f) = n.transpose();
  }
  return N;
}

Points face_normals(const TriangleMesh& mesh) { return face_normals(mesh.V, mesh.F); }

Eigen::VectorXd face_areas(const Points& V, const Triangles& F) {
  check_indices(V, F);
  Eigen::VectorXd A(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) A[f] = 0.5 * cross_of(V, F, f).norm();
  return A;
}

Eigen::VectorXd face_areas(const TriangleMesh& mesh) { return face_areas(mesh.V, mesh.F); }

Points vertex_normals(const Points& V, const Triangles& F) {
  check_indices(V, F);
  Points N = Points::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3d n = cross_of(V, F, f).transpose();  // |n| = 2 * area
    for (int c = 0; c < 3; ++c) N.row(F(f, c)) += n;
  }
  for (Eigen::Index v = 0; v < N.rows(); ++v) normalise_or_zero(N.row(v));
  return N;
}

Points vertex_normals(const TriangleMesh& mesh) { return vertex_normals(mesh.V, mesh.F); }

}  // namespace breastfit::mesh
