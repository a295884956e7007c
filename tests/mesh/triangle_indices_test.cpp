#include "breastfit/mesh/triangle_indices.h"

#include <gtest/gtest.h>

#include <string>

#include "breastfit/core/errors.h"

namespace breastfit::mesh {
namespace {

TEST(TriangleIndices, InRangeIndicesPass) {
  Triangles F(2, 3);
  F << 0, 1, 2, 2, 1, 3;
  EXPECT_NO_THROW(check_triangle_indices(F, 4));
  EXPECT_NO_THROW(check_triangle_indices(Triangles(0, 3), 0));
}

TEST(TriangleIndices, FirstBadIndexIsNamed) {
  Triangles F(3, 3);
  F << 0, 1, 2, 2, 1, 4, 0, -1, 2;
  try {
    check_triangle_indices(F, 4);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()), "triangle 1 has vertex index 4 outside [0, 4)");
  }
  F(1, 2) = 3;
  EXPECT_THROW(check_triangle_indices(F, 4), InvalidInput);  // the -1 of triangle 2
}

}  // namespace
}  // namespace breastfit::mesh
