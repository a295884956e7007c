#include "breastfit/mesh/components.h"

#include <gtest/gtest.h>

#include <cstdint>

#include "breastfit/core/errors.h"

namespace breastfit::mesh {
namespace {

TEST(Components, ThreePiecesSortedBySize) {
  // piece A: 1 triangle (0,1,2); piece B: 3 triangles fan around 3; piece C: 2 triangles touching
  // only at a vertex (bow tie, one component); vertex 14 unreferenced.
  Points V = Points::Zero(15, 3);
  Triangles F(6, 3);
  F << 0, 1, 2,          // A
      3, 4, 5, 3, 5, 6, 3, 6, 7,  // B
      8, 9, 10, 8, 11, 12;        // C (shares vertex 8)
  const Components c = connected_components(F, 15);
  ASSERT_EQ(c.count(), 3);
  EXPECT_EQ(c.face_count, (std::vector<Index>{3, 2, 1}));
  EXPECT_EQ(c.vertex_count, (std::vector<Index>{5, 5, 3}));
  EXPECT_EQ(c.face_label, (std::vector<Index>{2, 0, 0, 0, 1, 1}));
  EXPECT_EQ(c.vertex_label[0], 2);
  EXPECT_EQ(c.vertex_label[7], 0);
  EXPECT_EQ(c.vertex_label[12], 1);
  EXPECT_FALSE(c.vertex_label[13].has_value());
  EXPECT_FALSE(c.vertex_label[14].has_value());
}

TEST(Components, TiesOrderedByFirstTriangle) {
  Triangles F(2, 3);
  F << 3, 4, 5, 0, 1, 2;
  const Components c = connected_components(F, 6);
  EXPECT_EQ(c.face_label, (std::vector<Index>{0, 1}));
}

TEST(Components, ChainMergesThroughSharedVertices) {
  // Triangles linked pairwise through single vertices end up in one component regardless of order.
  Triangles F(4, 3);
  F << 0, 1, 2, 5, 6, 7, 2, 3, 4, 4, 5, 8;
  const Components c = connected_components(F, 9);
  EXPECT_EQ(c.count(), 1);
  EXPECT_EQ(c.face_count[0], 4);
  EXPECT_EQ(c.vertex_count[0], 9);
}

TEST(Components, PointCloudHasNone) {
  TriangleMesh cloud;
  cloud.V = Points::Random(10, 3);
  const Components c = connected_components(cloud);
  EXPECT_EQ(c.count(), 0);
  ASSERT_EQ(c.vertex_label.size(), 10u);
  EXPECT_FALSE(c.vertex_label[3].has_value());
}

TEST(Components, OutOfRangeThrows) {
  Triangles F(1, 3);
  F << 0, 1, 3;
  EXPECT_THROW(connected_components(F, 3), InvalidInput);
  TriangleMesh m;
  m.V = Points::Zero(3, 3);
  m.F = F;
  EXPECT_THROW(component_size_per_vertex(m), InvalidInput);
}

// The sizes without the labels: each vertex's component's face_count, 0 for an unused vertex —
// on the three pieces above and on random triangles over many vertices (pieces of every size).
TEST(Components, SizePerVertexIsTheLabelledComponentsFaceCount) {
  const auto expect_same = [](const TriangleMesh& m) {
    const Components c = connected_components(m);
    const std::vector<Index> size = component_size_per_vertex(m);
    ASSERT_EQ(size.size(), c.vertex_label.size());
    for (size_t v = 0; v < size.size(); ++v)
      EXPECT_EQ(size[v], c.vertex_label[v] ? c.face_count[static_cast<size_t>(*c.vertex_label[v])] : 0) << v;
  };
  TriangleMesh pieces;
  pieces.V = Points::Zero(15, 3);
  pieces.F.resize(6, 3);
  pieces.F << 0, 1, 2, 3, 4, 5, 3, 5, 6, 3, 6, 7, 8, 9, 10, 8, 11, 12;
  expect_same(pieces);
  TriangleMesh random;
  random.V = Points::Zero(3000, 3);
  random.F.resize(700, 3);
  std::uint64_t state = 12345;
  for (Index f = 0; f < random.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      random.F(f, c) = static_cast<Index>((state >> 33) % 3000);
    }
  expect_same(random);
  TriangleMesh cloud;
  cloud.V = Points::Zero(4, 3);
  EXPECT_EQ(component_size_per_vertex(cloud), (std::vector<Index>(4, 0)));
}

}  // namespace
}  // namespace breastfit::mesh
