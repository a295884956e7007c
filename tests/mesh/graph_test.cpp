#include "breastfit/mesh/graph.h"

#include <gtest/gtest.h>

#include <cmath>

#include "breastfit/core/errors.h"
#include "support/grid_mesh.h"

namespace breastfit::mesh {
namespace {

/// A path 0 – 1 – 2 – 3 along x (unit steps) made of thin triangles through apex vertices 4..6,
/// plus a separate triangle 7, 8, 9.
TriangleMesh strip_and_island() {
  TriangleMesh m;
  m.V.resize(10, 3);
  m.V << 0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0,  //
      0.5, 5, 0, 1.5, 5, 0, 2.5, 5, 0,         // apices far away: never on a shortest path
      10, 0, 0, 11, 0, 0, 10, 1, 0;
  m.F.resize(4, 3);
  m.F << 0, 1, 4, 1, 2, 5, 2, 3, 6, 7, 8, 9;
  return m;
}

Index vertex_at(const TriangleMesh& m, double x, double y) {
  for (Index v = 0; v < m.num_vertices(); ++v)
    if (std::abs(m.V(v, 0) - x) < 1e-9 && std::abs(m.V(v, 1) - y) < 1e-9) return v;
  return -1;
}

TEST(Graph, EdgeDistancesAlongAPath) {
  const TriangleMesh m = strip_and_island();
  const AdjacencyLists nbr = vertex_neighbours(m);
  const std::vector<double> d = edge_distances(m.V, nbr, {0});
  EXPECT_EQ(d[0], 0.0);
  EXPECT_DOUBLE_EQ(d[1], 1.0);
  EXPECT_DOUBLE_EQ(d[2], 2.0);
  EXPECT_DOUBLE_EQ(d[3], 3.0);
  EXPECT_NEAR(d[4], std::hypot(0.5, 5.0), 1e-12);
  EXPECT_TRUE(std::isinf(d[7]));  // another piece
}

TEST(Graph, EdgeDistancesStopAtMaxDistanceAndTakeNearestSource) {
  const TriangleMesh m = strip_and_island();
  const AdjacencyLists nbr = vertex_neighbours(m);
  const std::vector<double> d = edge_distances(m.V, nbr, {0, 3, 3}, 1.0);
  EXPECT_EQ(d[0], 0.0);
  EXPECT_EQ(d[3], 0.0);
  EXPECT_DOUBLE_EQ(d[1], 1.0);  // exactly at the limit: reached
  EXPECT_DOUBLE_EQ(d[2], 1.0);  // from vertex 3
  EXPECT_TRUE(std::isinf(d[4]));
  const std::vector<double> none = edge_distances(m.V, nbr, {});
  for (double x : none) EXPECT_TRUE(std::isinf(x));
  EXPECT_THROW(edge_distances(m.V, nbr, {10}), InvalidInput);
  EXPECT_THROW(edge_distances(m.V, vertex_neighbours(m.F, 11), {0}), InvalidInput);
}

TEST(Graph, EdgeDistancesOnGridAreManhattanOrDiagonal) {
  const TriangleMesh m = test::grid_mesh(3, 1.0);
  const AdjacencyLists nbr = vertex_neighbours(m);
  const Index c = vertex_at(m, 0, 0);
  ASSERT_GE(c, 0);
  const std::vector<double> d = edge_distances(m.V, nbr, {c});
  for (Index v = 0; v < m.num_vertices(); ++v) {
    const double x = std::abs(m.V(v, 0)), y = std::abs(m.V(v, 1));
    // Between the straight line and the axis-parallel (Manhattan) path.
    EXPECT_GE(d[static_cast<size_t>(v)], std::hypot(x, y) - 1e-12);
    EXPECT_LE(d[static_cast<size_t>(v)], x + y + 1e-12);
  }
}

TEST(Graph, EdgePathFinderFindsShortestPathAndReusesScratch) {
  const TriangleMesh m = strip_and_island();
  const AdjacencyLists nbr = vertex_neighbours(m);
  EdgePathFinder finder(m.V, nbr);
  EXPECT_EQ(finder.path(0, 3, 1000), (std::vector<Index>{1, 2, 3}));
  EXPECT_EQ(finder.path(3, 0, 1000), (std::vector<Index>{2, 1, 0}));  // scratch was reset
  EXPECT_EQ(finder.path(2, 2, 1000), std::vector<Index>{});
  EXPECT_TRUE(finder.path(0, 8, 1000).empty());  // another piece
  EXPECT_TRUE(finder.path(0, 3, 1).empty());     // out of budget
  EXPECT_EQ(finder.path(0, 2, 1000), (std::vector<Index>{1, 2}));
}

TEST(Graph, EdgePathOnGridHasEdgeDistanceLength) {
  const TriangleMesh m = test::grid_mesh(4, 2.0);
  const AdjacencyLists nbr = vertex_neighbours(m);
  const Index a = vertex_at(m, -8, -6), b = vertex_at(m, 6, 8);
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  EdgePathFinder finder(m.V, nbr);
  const std::vector<Index> p = finder.path(a, b, 100000);
  ASSERT_FALSE(p.empty());
  EXPECT_EQ(p.back(), b);
  double length = 0;
  Index prev = a;
  for (Index v : p) {
    EXPECT_TRUE(nbr.contains(prev, v));
    length += (m.V.row(prev) - m.V.row(v)).norm();
    prev = v;
  }
  EXPECT_NEAR(length, edge_distances(m.V, nbr, {a})[static_cast<size_t>(b)], 1e-9);
}

TEST(Graph, FloodFillLabelsPiecesAndStopsAtBlockedVertices) {
  const TriangleMesh m = strip_and_island();
  const AdjacencyLists nbr = vertex_neighbours(m);
  std::vector<int> labels(10, -1);
  flood_fill(nbr, 0, 0, labels);
  flood_fill(nbr, 7, 1, labels);
  EXPECT_EQ(labels, (std::vector<int>{0, 0, 0, 0, 0, 0, 0, 1, 1, 1}));

  // Blocking vertices 1 and 5 cuts the strip: {0, 4} | {2, 3, 6}.
  std::vector<char> blocked(10, 0);
  blocked[1] = blocked[5] = 1;
  std::vector<int> cut(10, -1);
  flood_fill(nbr, 0, 0, cut, &blocked);
  flood_fill(nbr, 3, 1, cut, &blocked);
  EXPECT_EQ(cut, (std::vector<int>{0, -1, 1, 1, 0, -1, 1, -1, -1, -1}));
}

}  // namespace
}  // namespace breastfit::mesh
