#include "breastfit/mesh/index_triangulation.h"

#include <gtest/gtest.h>

#include <vector>

namespace breastfit::mesh {
namespace {

TEST(IndexTriangulation, FanKeepsTheFirstCornerAndSkipsRepeats) {
  const Index quad[] = {0, 1, 2, 2, 3};
  std::vector<Index> tris;
  EXPECT_EQ(append_fan_triangles(quad, 5, tris), 2);
  EXPECT_EQ(tris, (std::vector<Index>{0, 1, 2, 0, 2, 3}));
}

TEST(IndexTriangulation, StripAlternatesWindingAndSkipsRepeats) {
  const Index strip[] = {0, 1, 2, 3, 4, 4, 5};
  std::vector<Index> tris{9, 9, 9};  // appended to, never cleared
  EXPECT_EQ(append_strip_triangles(strip, 7, tris), 3);
  EXPECT_EQ(tris, (std::vector<Index>{9, 9, 9, 0, 1, 2, 2, 1, 3, 2, 3, 4}));
}

TEST(IndexTriangulation, FewerThanThreeIndicesAppendNothing) {
  const Index two[] = {0, 1};
  std::vector<Index> tris;
  EXPECT_EQ(append_strip_triangles(two, 2, tris), 0);
  EXPECT_EQ(append_fan_triangles(two, 2, tris), 0);
  EXPECT_EQ(append_strip_triangles(two, 0, tris), 0);
  EXPECT_TRUE(tris.empty());
}

}  // namespace
}  // namespace breastfit::mesh
