#pragma once
/// \file Two meshes equal field by field, bit for bit (positions, faces, normals, colours,
/// texture coordinates and their faces), as gtest expectations.
#include <gtest/gtest.h>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::test {

inline void expect_same_mesh(const TriangleMesh& a, const TriangleMesh& b) {
  EXPECT_EQ(a.V, b.V);
  EXPECT_EQ(a.F, b.F);
  EXPECT_EQ(a.N, b.N);
  EXPECT_EQ(a.C, b.C);
  EXPECT_EQ(a.UV, b.UV);
  EXPECT_EQ(a.FUV, b.FUV);
}

}  // namespace breastfit::test
