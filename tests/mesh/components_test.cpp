#include "breastfit/mesh/components.h"

#include <gtest/gtest.h>

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
}

}  // namespace
}  // namespace breastfit::mesh
