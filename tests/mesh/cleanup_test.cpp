#include "breastfit/mesh/cleanup.h"

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"

namespace breastfit::mesh {
namespace {

/// Two triangles of a square (vertices 0-3), a degenerate repeated-index triangle, a collinear
/// triangle (4,5,6), an isolated single triangle (7,8,9), an unreferenced vertex 10.
TriangleMesh messy() {
  TriangleMesh m;
  m.V.resize(11, 3);
  m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,  // square
      5, 0, 0, 6, 0, 0, 7, 0, 0,              // collinear
      10, 0, 0, 11, 0, 0, 10, 1, 0,           // lone triangle
      99, 99, 99;                             // unreferenced
  m.F.resize(5, 3);
  m.F << 0, 1, 2, 0, 2, 3, 1, 1, 2, 4, 5, 6, 7, 8, 9;
  m.N = m.V * 2.0;  // per-vertex attribute that must follow the vertices
  m.C.resize(11, 3);
  for (int v = 0; v < 11; ++v) m.C.row(v) << v, 2 * v, 3 * v;
  return m;
}

TEST(Cleanup, DegenerateFaces) {
  const TriangleMesh m = messy();
  const auto bad = degenerate_faces(m.V, m.F);
  EXPECT_EQ(bad, (std::vector<bool>{false, false, true, true, false}));
  EXPECT_EQ(count_degenerate_faces(m.V, m.F), 2);
  // A thin but valid sliver is kept at the default tolerance, caught by a looser one.
  Points V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0.5, 1e-4, 0;
  Triangles F(1, 3);
  F << 0, 1, 2;
  EXPECT_EQ(count_degenerate_faces(V, F), 0);
  EXPECT_EQ(count_degenerate_faces(V, F, 1e-3), 1);
  EXPECT_THROW(degenerate_faces(V, F, -1.0), InvalidInput);
}

TEST(Cleanup, DegenerateIsScaleInvariant) {
  Points V(3, 3);
  V << 0, 0, 0, 1e-6, 0, 0, 0, 1e-6, 0;  // tiny but well-shaped
  Triangles F(1, 3);
  F << 0, 1, 2;
  EXPECT_EQ(count_degenerate_faces(V, F), 0);
}

TEST(Cleanup, RemoveUnreferencedVerticesCompactsAttributes) {
  TriangleMesh m = messy();
  const auto map = remove_unreferenced_vertices(m);
  ASSERT_EQ(map.size(), 11u);
  EXPECT_FALSE(map[10].has_value());
  EXPECT_EQ(map[9], 9);
  EXPECT_EQ(m.num_vertices(), 10);
  EXPECT_EQ(m.N.rows(), 10);
  EXPECT_EQ(m.C.rows(), 10);

  TriangleMesh only_lone = messy();
  Triangles F(1, 3);
  F << 7, 8, 9;
  only_lone.F = F;
  const auto map2 = remove_unreferenced_vertices(only_lone);
  EXPECT_EQ(only_lone.num_vertices(), 3);
  EXPECT_EQ(map2[7], 0);
  EXPECT_EQ(map2[9], 2);
  EXPECT_FALSE(map2[0].has_value());
  EXPECT_EQ(only_lone.F, (Triangles(1, 3) << 0, 1, 2).finished());
  EXPECT_EQ(only_lone.V.row(1), Eigen::RowVector3d(11, 0, 0));
  EXPECT_EQ(only_lone.N.row(1), Eigen::RowVector3d(22, 0, 0));
  EXPECT_EQ(only_lone.C(2, 2), 27);
}

TEST(Cleanup, PointCloudUntouched) {
  TriangleMesh cloud;
  cloud.V = Points::Random(5, 3);
  const auto map = remove_unreferenced_vertices(cloud);
  EXPECT_EQ(cloud.num_vertices(), 5);
  EXPECT_EQ(map[4], 4);
}

TEST(Cleanup, RemoveSmallComponentsAndFullCleanup) {
  TriangleMesh m = messy();
  m.FUV = m.F;  // per-corner texture indices follow their triangles
  m.UV = TexCoords::Zero(11, 2);
  CleanupOptions opt;
  opt.remove_small_components = true;
  opt.min_component_faces = 2;
  const CleanupSummary s = cleanup(m, opt);
  EXPECT_EQ(s.removed_degenerate_faces, 2);
  EXPECT_EQ(s.removed_components, 1);       // the lone triangle
  EXPECT_EQ(s.removed_component_faces, 1);
  EXPECT_EQ(s.removed_vertices, 7);         // 4,5,6 (collinear), 7,8,9, 10
  EXPECT_EQ(m.num_vertices(), 4);
  EXPECT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.FUV.rows(), 2);
  EXPECT_EQ(*s.old_to_new_vertex[3], 3);
  EXPECT_FALSE(s.old_to_new_vertex[7].has_value());
}

TEST(Cleanup, OptionsValidate) {
  CleanupOptions opt;
  opt.min_component_faces = 0;
  EXPECT_THROW(opt.validate(), InvalidInput);
  opt = {};
  opt.relative_area_tolerance = -1;
  EXPECT_THROW(opt.validate(), InvalidInput);
  TriangleMesh m = messy();
  EXPECT_THROW(remove_small_components(m, 0), InvalidInput);
  CleanupOptions keep_all;
  keep_all.remove_degenerate = false;
  keep_all.remove_unreferenced = false;
  const CleanupSummary s = cleanup(m, keep_all);
  EXPECT_EQ(m.num_faces(), 5);
  EXPECT_EQ(s.old_to_new_vertex.size(), 11u);
  EXPECT_EQ(s.old_to_new_vertex[10], 10);
}

}  // namespace
}  // namespace breastfit::mesh
