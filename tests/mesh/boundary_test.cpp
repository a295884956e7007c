#include "breastfit/mesh/boundary.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "breastfit/core/errors.h"

namespace breastfit::mesh {
namespace {

/// n x m grid of unit squares in the z=0 plane, two CCW triangles per square.
TriangleMesh grid(int n, int m, double h = 1.0) {
  TriangleMesh g;
  g.V.resize((n + 1) * (m + 1), 3);
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) g.V.row(j * (n + 1) + i) << i * h, j * h, 0.0;
  g.F.resize(2 * n * m, 3);
  int f = 0;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const Index a = j * (n + 1) + i, b = a + 1, c = a + (n + 1), d = c + 1;
      g.F.row(f++) << a, b, d;
      g.F.row(f++) << a, d, c;
    }
  return g;
}

/// Removes the two triangles of square (i, j) of a grid made by grid(n, m).
TriangleMesh punch(const TriangleMesh& g, int n, int i, int j) {
  TriangleMesh h = g;
  const int f0 = 2 * (j * n + i);
  Triangles F(g.F.rows() - 2, 3);
  int k = 0;
  for (int f = 0; f < g.F.rows(); ++f)
    if (f != f0 && f != f0 + 1) F.row(k++) = g.F.row(f);
  h.F = F;
  return h;
}

TEST(Boundary, GridBorder) {
  const TriangleMesh g = grid(3, 2);
  const auto edges = boundary_edges(g.F);
  EXPECT_EQ(edges.size(), 2u * (3 + 2));
  const auto flags = boundary_vertices(g);
  // Interior vertices of a 4x3 vertex grid: (1,1), (2,1).
  int interior = 0;
  for (bool b : flags) interior += !b;
  EXPECT_EQ(interior, 2);
  EXPECT_FALSE(flags[5]);
  EXPECT_FALSE(flags[6]);
  EXPECT_TRUE(flags[0]);
  const auto loops = boundary_loops(g);
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].size(), 10u);
  EXPECT_NEAR(loop_length(g.V, loops[0]), 10.0, 1e-12);
  EXPECT_EQ(count_non_manifold_edges(g.F), 0);
}

TEST(Boundary, LoopFollowsTriangleOrientation) {
  const TriangleMesh g = grid(2, 2);
  const auto loops = boundary_loops(g);
  ASSERT_EQ(loops.size(), 1u);
  // For CCW triangles seen from +z the outer border runs CCW: signed area > 0.
  double area2 = 0.0;
  const auto& L = loops[0];
  for (size_t i = 0; i < L.size(); ++i) {
    const auto a = g.V.row(L[i]), b = g.V.row(L[(i + 1) % L.size()]);
    area2 += a.x() * b.y() - b.x() * a.y();
  }
  EXPECT_NEAR(area2, 2.0 * 4.0, 1e-12);
  // Consecutive loop vertices are joined by boundary edges.
  const auto edges = boundary_edges(g.F);
  std::set<std::pair<Index, Index>> directed;
  for (const auto& e : edges) directed.insert({e[0], e[1]});
  for (size_t i = 0; i < L.size(); ++i)
    EXPECT_TRUE(directed.count({L[i], L[(i + 1) % L.size()]})) << i;
}

TEST(Boundary, HoleMakesSecondLoop) {
  const int n = 4;
  const TriangleMesh h = punch(grid(n, 4), n, 1, 2);
  const auto loops = boundary_loops(h);
  ASSERT_EQ(loops.size(), 2u);
  std::vector<double> lengths{loop_length(h.V, loops[0]), loop_length(h.V, loops[1])};
  std::sort(lengths.begin(), lengths.end());
  EXPECT_NEAR(lengths[0], 4.0, 1e-12);
  EXPECT_NEAR(lengths[1], 16.0, 1e-12);
  EXPECT_EQ(boundary_edges(h.F).size(), 16u + 4u);
}

TEST(Boundary, ClosedMeshHasNoBoundary) {
  TriangleMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  EXPECT_TRUE(boundary_edges(m.F).empty());
  EXPECT_TRUE(boundary_loops(m).empty());
  const auto flags = boundary_vertices(m);
  EXPECT_EQ(std::count(flags.begin(), flags.end(), true), 0);
}

TEST(Boundary, NonManifoldFinEdge) {
  // Three triangles sharing edge (0, 1).
  Points V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1;
  Triangles F(3, 3);
  F << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  EXPECT_EQ(count_non_manifold_edges(F), 1);
  // The shared edge is not a boundary edge; the 6 outer edges are.
  EXPECT_EQ(boundary_edges(F).size(), 6u);
}

TEST(Boundary, PinchedBordersSplitIntoTwoLoops) {
  // Two triangles touching at vertex 0 only (a bow tie): two loops of 3.
  Points V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0;
  Triangles F(2, 3);
  F << 0, 1, 2, 0, 3, 4;
  const auto loops = boundary_loops(F);
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].size(), 3u);
  EXPECT_EQ(loops[1].size(), 3u);
}

TEST(Boundary, PointCloudAndRangeChecks) {
  Triangles none(0, 3);
  EXPECT_TRUE(boundary_loops(none).empty());
  EXPECT_EQ(boundary_vertices(none, 3), std::vector<bool>(3, false));
  Triangles F(1, 3);
  F << 0, 1, 5;
  EXPECT_THROW(boundary_vertices(F, 3), InvalidInput);
  EXPECT_EQ(loop_length(Points::Zero(1, 3), {0}), 0.0);
}

}  // namespace
}  // namespace breastfit::mesh
