#include "breastfit/mesh/normals.h"

#include <gtest/gtest.h>

#include <cmath>

#include "breastfit/core/errors.h"
#include "breastfit/core/rng.h"

namespace breastfit::mesh {
namespace {

/// Closed, outward-oriented octahedron of radius r.
TriangleMesh octahedron(double r = 1.0) {
  TriangleMesh m;
  m.V.resize(6, 3);
  m.V << r, 0, 0, -r, 0, 0, 0, r, 0, 0, -r, 0, 0, 0, r, 0, 0, -r;
  m.F.resize(8, 3);
  m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return m;
}

TEST(Normals, FaceNormalsAndAreasOfRightTriangle) {
  Points V(3, 3);
  V << 0, 0, 0, 2, 0, 0, 0, 3, 0;
  Triangles F(1, 3);
  F << 0, 1, 2;
  const Points N = face_normals(V, F);
  EXPECT_NEAR(N(0, 2), 1.0, 1e-15);
  EXPECT_NEAR(N.row(0).head<2>().norm(), 0.0, 1e-15);
  EXPECT_NEAR(face_areas(V, F)[0], 3.0, 1e-15);
  F << 0, 2, 1;  // reversed winding flips the normal
  EXPECT_NEAR(face_normals(V, F)(0, 2), -1.0, 1e-15);
}

TEST(Normals, DegenerateFaceHasZeroNormal) {
  Points V(3, 3);
  V << 0, 0, 0, 1, 1, 1, 2, 2, 2;
  Triangles F(1, 3);
  F << 0, 1, 2;
  EXPECT_EQ(face_normals(V, F).row(0).norm(), 0.0);
  EXPECT_EQ(face_areas(V, F)[0], 0.0);
  EXPECT_EQ(vertex_normals(V, F).norm(), 0.0);
}

TEST(Normals, OctahedronVertexNormalsPointOutward) {
  const TriangleMesh m = octahedron(2.0);
  const Points N = vertex_normals(m);
  ASSERT_EQ(N.rows(), 6);
  for (Index v = 0; v < 6; ++v) {
    const Vec3 expected = m.V.row(v).normalized().transpose();
    EXPECT_NEAR((N.row(v).transpose() - expected).norm(), 0.0, 1e-12) << "vertex " << v;
  }
  EXPECT_NEAR(face_areas(m).sum(), 4.0 * std::sqrt(3.0) * 2.0 * 2.0, 1e-9);  // 4 sqrt(3) r^2
}

TEST(Normals, AreaWeighting) {
  // Vertex 0 shared by a big triangle in the z=0 plane and a small one in the x=0 plane:
  // the normal leans towards the big triangle's normal in proportion to the areas.
  Points V(5, 3);
  V << 0, 0, 0, 4, 0, 0, 0, 4, 0, 0, 0, 1, 0, -1, 0;
  Triangles F(2, 3);
  F << 0, 1, 2,   // area 8, normal +z
      0, 3, 4;    // area 0.5, normal (0,0,1)x(0,-1,0) = +x
  const Points N = vertex_normals(V, F);
  const Vec3 expected = Vec3(0.5, 0, 8).normalized();
  EXPECT_NEAR((N.row(0).transpose() - expected).norm(), 0.0, 1e-12);
  EXPECT_NEAR(N(1, 2), 1.0, 1e-12);
}

TEST(Normals, UnreferencedVertexGetsZeroNormal) {
  TriangleMesh m = octahedron();
  m.V.conservativeResize(7, 3);
  m.V.row(6) << 5, 5, 5;
  const Points N = vertex_normals(m);
  EXPECT_EQ(N.row(6).norm(), 0.0);
  EXPECT_NEAR(N.row(0).norm(), 1.0, 1e-12);
}

TEST(Normals, OutOfRangeIndexThrows) {
  TriangleMesh m = octahedron();
  m.F(3, 1) = 6;
  EXPECT_THROW(vertex_normals(m), InvalidInput);
  EXPECT_THROW(face_normals(m), InvalidInput);
  m.F(3, 1) = -1;
  EXPECT_THROW(face_areas(m), InvalidInput);
}

TEST(Normals, TranslationAndScaleInvariant) {
  const TriangleMesh m = octahedron();
  TriangleMesh moved = m;
  moved.V = (m.V * 250.0).rowwise() + Eigen::RowVector3d(10, -20, 30);
  EXPECT_LT((vertex_normals(m) - vertex_normals(moved)).norm(), 1e-12);
  EXPECT_NEAR(face_areas(moved).sum(), face_areas(m).sum() * 250.0 * 250.0, 1e-6);
}

}  // namespace
}  // namespace breastfit::mesh
