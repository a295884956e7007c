#include "breastfit/io/read_obj.h"

#include <gtest/gtest.h>

#include <string>

#include "breastfit/core/errors.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

TEST(ReadObj, FixtureWithAllIndexFormsNegativeIndicesAndContinuation) {
  const TriangleMesh m = read_obj(test::data_dir() / "meshes" / "tetra.obj");
  ASSERT_EQ(m.num_vertices(), 4);
  ASSERT_EQ(m.num_faces(), 4);
  EXPECT_EQ(m.F.row(0), (Eigen::RowVector3i(0, 2, 1)));
  EXPECT_EQ(m.F.row(1), (Eigen::RowVector3i(0, 1, 3)));  // -4 -3 -1 with 4 vertices
  EXPECT_EQ(m.F.row(2), (Eigen::RowVector3i(0, 3, 2)));  // continued on the next line
  ASSERT_TRUE(m.has_texcoords());
  EXPECT_EQ(m.UV.rows(), 3);
  EXPECT_EQ(m.FUV.row(0), (Eigen::RowVector3i(0, 2, 1)));
  EXPECT_EQ(m.FUV.row(3), (Eigen::RowVector3i(1, 2, 0)));
  // Vertex 0 is used with vn 1 and vn 2 (conflict: normalised average); vertex 1 likewise.
  ASSERT_TRUE(m.has_normals()) << "every vertex is reached by a corner with a normal";
  EXPECT_NEAR(m.N.row(0).norm(), 1.0, 1e-12);
  EXPECT_NEAR(m.N(0, 0), 0.0, 1e-12);
  EXPECT_NEAR(m.N(0, 1), -std::sqrt(0.5), 1e-12);
  EXPECT_EQ(m.N.row(2), (Eigen::RowVector3d(0, 0, -1)));  // vertex 2 only ever uses vn 1
}

TEST(ReadObj, PolygonsAreFanTriangulatedAndWAndGroupsIgnored) {
  const std::string s =
      "o thing\ng a b\nv 0 0 0 1\nv 1 0 0 1\nv 1 1 0 1\nv 0 1 0 1\nv 0.5 0.5 1\n"
      "s 1\nusemtl m\nf 1 2 3 4 5\nl 1 2\np 3\n";
  const TriangleMesh m = read_obj_from_memory(s, "fan.obj");
  ASSERT_EQ(m.num_vertices(), 5);
  ASSERT_EQ(m.num_faces(), 3);
  EXPECT_EQ(m.F.row(2), (Eigen::RowVector3i(0, 3, 4)));
  EXPECT_FALSE(m.has_colors());
  EXPECT_FALSE(m.has_texcoords());
  EXPECT_FALSE(m.has_normals());
}

/// The L-shaped hexagon (2,1) (1,1) (1,2) (0,2) (0,0) (2,0) of area 3, counter-clockwise seen
/// from +z, tilted out of the xy plane; its first corner's fan would cover the notch.
std::string l_shaped_obj() {
  const double xy[6][2] = {{2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}, {2, 0}};
  std::string s;
  for (const auto& p : xy)
    s += "v " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(0.5 * p[0]) + "\n";
  return s + "f 1 2 3 4 5 6\n";
}

TEST(ReadObj, ConcavePolygonIsEarClippedNotFanned) {
  const TriangleMesh m = read_obj_from_memory(l_shaped_obj(), "l.obj");
  ASSERT_EQ(m.num_faces(), 4);
  double area = 0;
  for (Eigen::Index f = 0; f < m.num_faces(); ++f) {
    const Vec3 a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    const Vec3 n = (b - a).cross(c - a);
    EXPECT_GT(n.z(), 0) << "triangle " << f << " keeps the polygon's winding";
    area += 0.5 * n.z();  // the area projected on xy
    // No triangle covers the notch x, y in (1, 2): its centroid is inside the L.
    const Vec3 g = (a + b + c) / 3;
    EXPECT_FALSE(g.x() > 1 && g.y() > 1) << "triangle " << f << " covers the notch";
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
}

TEST(ReadObj, ConvexPolygonWithCollinearCornersKeepsTheFan) {
  const TriangleMesh m =
      read_obj_from_memory("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4 5\n", "c.obj");
  ASSERT_EQ(m.num_faces(), 3);
  EXPECT_EQ(m.F.row(0), (Eigen::RowVector3i(0, 1, 2)));
  EXPECT_EQ(m.F.row(1), (Eigen::RowVector3i(0, 2, 3)));
  EXPECT_EQ(m.F.row(2), (Eigen::RowVector3i(0, 3, 4)));
}

TEST(ReadObj, VertexColoursKeptOnlyWhenEveryVertexHasThem) {
  const TriangleMesh a =
      read_obj_from_memory("v 0 0 0 1 0 0.5\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n", "a.obj");
  ASSERT_TRUE(a.has_colors());
  EXPECT_EQ(a.C(0, 0), 255);
  EXPECT_EQ(a.C(0, 2), 128);
  const TriangleMesh b =
      read_obj_from_memory("v 0 0 0 10 20 30\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "b.obj");
  EXPECT_FALSE(b.has_colors());
  const TriangleMesh c = read_obj_from_memory("v 0 0 0 10 20 300\nv 1 0 0 1 2 3\n", "c.obj");
  ASSERT_TRUE(c.has_colors());  // values above 1: taken as 0..255, clamped
  EXPECT_EQ(c.C(0, 0), 10);
  EXPECT_EQ(c.C(0, 2), 255);
  EXPECT_TRUE(c.is_point_cloud());
}

TEST(ReadObj, MixedFacesWithAndWithoutTexcoordsDropTexcoords) {
  const TriangleMesh m = read_obj_from_memory(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n", "mixed.obj");
  EXPECT_EQ(m.num_faces(), 2);
  EXPECT_FALSE(m.has_texcoords());
}

TEST(ReadObj, PointCloudWithOneNormalPerVertex) {
  const TriangleMesh m =
      read_obj_from_memory("v 1 2 3\r\nv 4 5 6\r\nvn 0 0 1\r\nvn 0 1 0\r\n", "pc.obj");
  EXPECT_TRUE(m.is_point_cloud());
  ASSERT_TRUE(m.has_normals());
  EXPECT_EQ(m.N(1, 1), 1.0);
  EXPECT_EQ(m.V(1, 2), 6.0);
}

}  // namespace
}  // namespace breastfit::io
