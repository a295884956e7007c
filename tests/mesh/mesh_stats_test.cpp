#include "breastfit/mesh/mesh_stats.h"

#include <gtest/gtest.h>

#include <limits>

#include "breastfit/core/errors.h"

namespace breastfit::mesh {
namespace {

/// n x n grid of h-sized squares in z=0, the square (1,1) removed (a hole), plus a separate
/// single triangle far away and a duplicated-index degenerate triangle on the grid.
TriangleMesh holey_grid(int n, double h) {
  TriangleMesh g;
  const int nv = (n + 1) * (n + 1);
  g.V.resize(nv + 3, 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) g.V.row(j * (n + 1) + i) << i * h, j * h, 0.0;
  g.V.row(nv) << 0, 0, 10 * h;
  g.V.row(nv + 1) << h, 0, 10 * h;
  g.V.row(nv + 2) << 0, h, 10 * h;
  std::vector<std::array<Index, 3>> tris;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i == 1 && j == 1) continue;
      const Index a = j * (n + 1) + i, b = a + 1, c = a + (n + 1), d = c + 1;
      tris.push_back({a, b, d});
      tris.push_back({a, d, c});
    }
  tris.push_back({nv, nv + 1, nv + 2});
  tris.push_back({0, 0, 1});
  g.F.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t f = 0; f < tris.size(); ++f) g.F.row(static_cast<Eigen::Index>(f)) << tris[f][0], tris[f][1], tris[f][2];
  return g;
}

TEST(MeshStats, CountsBoundariesComponents) {
  const double h = 40.0;  // mm-sized: 4 squares of 40 mm = 160 mm across
  const TriangleMesh g = holey_grid(4, h);
  const MeshStats s = mesh_stats(g);
  EXPECT_EQ(s.num_vertices, 25 + 3);
  EXPECT_EQ(s.num_faces, 2 * 15 + 2);
  EXPECT_FALSE(s.is_point_cloud);
  EXPECT_EQ(s.num_degenerate_faces, 1);
  EXPECT_EQ(s.num_non_manifold_edges, 0);
  EXPECT_EQ(s.num_components, 2);
  EXPECT_EQ(s.component_face_counts, (std::vector<Index>{31, 1}));
  EXPECT_EQ(s.num_unreferenced_vertices, 0);
  // Loops: outer border (16 h), the hole (4 h), the lone triangle (2 h + sqrt(2) h).
  ASSERT_EQ(s.boundary_loops.size(), 3u);
  EXPECT_NEAR(s.boundary_loops[0].length, 16 * h, 1e-9);
  EXPECT_EQ(s.boundary_loops[0].num_vertices, 16);
  EXPECT_NEAR(s.boundary_loops[1].length, 4 * h, 1e-9);
  EXPECT_NEAR(s.boundary_loops[2].length, (2 + std::sqrt(2.0)) * h, 1e-9);
  EXPECT_EQ(s.num_boundary_edges, 16 + 4 + 3);
  ASSERT_TRUE(s.edge_lengths.has_value());
  EXPECT_NEAR(s.edge_lengths->min, h, 1e-9);
  EXPECT_NEAR(s.edge_lengths->max, std::sqrt(2.0) * h, 1e-9);
  EXPECT_NEAR(s.edge_lengths->median, h, 1e-9);
  EXPECT_GT(s.edge_lengths->mean, h);
  EXPECT_LT(s.edge_lengths->mean, std::sqrt(2.0) * h);
  EXPECT_NEAR(s.max_extent, 10 * h, 1e-9);
  EXPECT_EQ(s.bbox_max, Vec3(4 * h, 4 * h, 10 * h));
  ASSERT_TRUE(s.units.has_value());
  EXPECT_EQ(*s.units, Units::Millimetres);
  EXPECT_TRUE(s.units_detected);
  EXPECT_NEAR(*s.max_extent_mm, 400.0, 1e-9);
  const std::string text = s.full();
  EXPECT_NE(text.find("components: 2"), std::string::npos) << text;
  EXPECT_NE(text.find("degenerate faces: 1"), std::string::npos) << text;
}

TEST(MeshStats, EdgeLengthMedianOddAndEven) {
  TriangleMesh t;
  t.V.resize(4, 3);
  t.V << 0, 0, 0, 3, 0, 0, 0, 4, 0, 3, 4, 1;  // edges 3, 4, 5 and more
  t.F.resize(1, 3);
  t.F << 0, 1, 2;
  const MeshStats s = mesh_stats(t, Units::Metres);
  ASSERT_TRUE(s.edge_lengths);
  EXPECT_EQ(s.edge_lengths->count, 3);
  EXPECT_NEAR(s.edge_lengths->median, 4.0, 1e-12);
  EXPECT_NEAR(s.edge_lengths->mean, 4.0, 1e-12);
  EXPECT_EQ(s.num_unreferenced_vertices, 1);
  EXPECT_FALSE(s.units_detected);
  EXPECT_NEAR(*s.max_extent_mm, 4000.0, 1e-9);
  TriangleMesh two;  // disjoint 3-4-5 and 6-8-10 triangles: sorted 3 4 5 6 8 10, median 5.5
  two.V.resize(6, 3);
  two.V << 0, 0, 0, 3, 0, 0, 0, 4, 0, 10, 0, 0, 16, 0, 0, 10, 8, 0;
  two.F.resize(2, 3);
  two.F << 0, 1, 2, 3, 4, 5;
  const MeshStats s2 = mesh_stats(two, Units::Metres);
  EXPECT_EQ(s2.edge_lengths->count, 6);
  EXPECT_NEAR(s2.edge_lengths->median, 5.5, 1e-12);
  EXPECT_NEAR(s2.edge_lengths->min, 3.0, 1e-12);
  EXPECT_NEAR(s2.edge_lengths->max, 10.0, 1e-12);
}

TEST(MeshStats, PointCloudAndAmbiguousUnits) {
  TriangleMesh cloud;
  cloud.V.resize(3, 3);
  cloud.V << 0, 0, 0, 20, 0, 0, 0, 10, 0;
  const MeshStats s = mesh_stats(cloud);
  EXPECT_TRUE(s.is_point_cloud);
  EXPECT_FALSE(s.edge_lengths.has_value());
  EXPECT_EQ(s.num_components, 0);
  EXPECT_FALSE(s.units.has_value());
  EXPECT_NE(s.units_problem.find("pass --units"), std::string::npos);
  EXPECT_NE(s.full().find("point cloud"), std::string::npos);
  cloud.V(1, 0) = std::numeric_limits<double>::infinity();
  const MeshStats s2 = mesh_stats(cloud, Units::Millimetres);
  EXPECT_EQ(s2.num_non_finite_vertices, 1);
  EXPECT_NEAR(s2.max_extent, 10.0, 1e-12);
}

TEST(MeshStats, BadIndexThrows) {
  TriangleMesh t;
  t.V = Points::Zero(2, 3);
  t.F.resize(1, 3);
  t.F << 0, 1, 2;
  EXPECT_THROW(mesh_stats(t), InvalidInput);
}

}  // namespace
}  // namespace breastfit::mesh
