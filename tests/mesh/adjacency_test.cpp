#include "breastfit/mesh/adjacency.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>

#include "breastfit/core/errors.h"
#include "support/grid_mesh.h"

namespace breastfit::mesh {
namespace {

std::vector<Index> row_of(const AdjacencyLists& a, Index r) {
  const auto s = a[r];
  return {s.begin(), s.end()};
}

/// Two triangles sharing edge 1–2, a degenerate triangle repeating vertex 3, vertex 5 unused.
Triangles small_mesh() {
  Triangles F(3, 3);
  F << 0, 1, 2,  //
      2, 1, 3,   //
      3, 3, 4;   // repeats vertex 3: only edge 3–4 is proper
  return F;
}

TEST(Adjacency, NeighboursSortedUniqueWithoutSelf) {
  const AdjacencyLists n = vertex_neighbours(small_mesh(), 6);
  ASSERT_EQ(n.num_rows(), 6);
  EXPECT_EQ(row_of(n, 0), (std::vector<Index>{1, 2}));
  EXPECT_EQ(row_of(n, 1), (std::vector<Index>{0, 2, 3}));
  EXPECT_EQ(row_of(n, 2), (std::vector<Index>{0, 1, 3}));
  EXPECT_EQ(row_of(n, 3), (std::vector<Index>{1, 2, 4}));
  EXPECT_EQ(row_of(n, 4), (std::vector<Index>{3}));
  EXPECT_EQ(n.size(5), 0);  // unused vertex
  EXPECT_TRUE(n.contains(1, 3));
  EXPECT_FALSE(n.contains(0, 3));
  EXPECT_FALSE(n.contains(3, 3));
  EXPECT_FALSE(n.contains(5, 0));
}

TEST(Adjacency, FacesAroundVertexAscendingOnce) {
  const AdjacencyLists f = vertex_faces(small_mesh(), 6);
  EXPECT_EQ(row_of(f, 0), (std::vector<Index>{0}));
  EXPECT_EQ(row_of(f, 1), (std::vector<Index>{0, 1}));
  EXPECT_EQ(row_of(f, 3), (std::vector<Index>{1, 2}));  // face 2 once, though it uses 3 twice
  EXPECT_EQ(row_of(f, 4), (std::vector<Index>{2}));
  EXPECT_EQ(f.size(5), 0);
}

TEST(Adjacency, UniqueEdgesSortedWithoutSelfEdges) {
  const auto e = unique_edges(small_mesh(), 6);
  const std::vector<std::array<Index, 2>> expected = {{0, 1}, {0, 2}, {1, 2}, {1, 3}, {2, 3}, {3, 4}};
  EXPECT_EQ(e, expected);
}

TEST(Adjacency, GridMatchesBruteForce) {
  const TriangleMesh m = test::grid_mesh(4, 2.0);
  const AdjacencyLists n = vertex_neighbours(m);
  const AdjacencyLists vf = vertex_faces(m);
  std::vector<std::set<Index>> nb(static_cast<size_t>(m.num_vertices()));
  std::vector<std::set<Index>> fb(static_cast<size_t>(m.num_vertices()));
  std::set<std::pair<Index, Index>> eb;
  for (Index f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Index a = m.F(f, k), b = m.F(f, (k + 1) % 3);
      nb[static_cast<size_t>(a)].insert(b);
      nb[static_cast<size_t>(b)].insert(a);
      fb[static_cast<size_t>(a)].insert(f);
      eb.insert({std::min(a, b), std::max(a, b)});
    }
  for (Index v = 0; v < m.num_vertices(); ++v) {
    EXPECT_EQ(row_of(n, v), std::vector<Index>(nb[static_cast<size_t>(v)].begin(), nb[static_cast<size_t>(v)].end()));
    EXPECT_EQ(row_of(vf, v), std::vector<Index>(fb[static_cast<size_t>(v)].begin(), fb[static_cast<size_t>(v)].end()));
  }
  const auto e = unique_edges(m.F, m.num_vertices());
  ASSERT_EQ(e.size(), eb.size());
  size_t i = 0;
  for (const auto& [a, b] : eb) {
    EXPECT_EQ(e[i][0], a);
    EXPECT_EQ(e[i][1], b);
    ++i;
  }
}

TEST(Adjacency, EmptyAndOutOfRange) {
  const AdjacencyLists n = vertex_neighbours(Triangles(0, 3), 3);
  EXPECT_EQ(n.num_rows(), 3);
  EXPECT_TRUE(n.items.empty());
  EXPECT_EQ(AdjacencyLists{}.num_rows(), 0);
  Triangles F = small_mesh();
  F(1, 2) = 6;
  EXPECT_THROW(vertex_neighbours(F, 6), InvalidInput);
  EXPECT_THROW(vertex_faces(F, 6), InvalidInput);
  F(1, 2) = -1;
  EXPECT_THROW(unique_edges(F, 6), InvalidInput);
}

}  // namespace
}  // namespace breastfit::mesh
