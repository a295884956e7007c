#include "breastfit/io/read_stl.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "breastfit/core/errors.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

void put_float(std::string& s, float v) {
  char b[4];
  std::memcpy(b, &v, 4);
  s.append(b, 4);
}

/// Binary STL of two triangles sharing an edge; the header deliberately starts with "solid".
std::string binary_two_triangles() {
  std::string s = "solid but actually binary";
  s.resize(80, ' ');
  const std::uint32_t n = 2;
  char b[4];
  std::memcpy(b, &n, 4);
  s.append(b, 4);
  const float tris[2][9] = {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 1, 1, 0, 0, 1, 0}};
  for (const auto& t : tris) {
    for (int k = 0; k < 3; ++k) put_float(s, k == 2 ? 1.f : 0.f);
    for (float v : t) put_float(s, v);
    s.append(2, '\0');
  }
  return s;
}

TEST(ReadStl, AsciiFixtureMergesIdenticalVertices) {
  const TriangleMesh m = read_stl(test::data_dir() / "meshes" / "tetra_ascii.stl");
  ASSERT_EQ(m.num_vertices(), 4);
  ASSERT_EQ(m.num_faces(), 4);
  EXPECT_EQ(m.V.row(0), (Eigen::RowVector3d(0, 0, 0)));
  EXPECT_EQ(m.F.row(0), (Eigen::RowVector3i(0, 1, 2)));
  EXPECT_EQ(m.F.row(3), (Eigen::RowVector3i(2, 1, 3)));
  EXPECT_FALSE(m.has_normals());
}

TEST(ReadStl, BinaryDetectedBySizeEvenWhenHeaderSaysSolid) {
  const TriangleMesh m = read_stl_from_memory(binary_two_triangles(), "two.stl");
  ASSERT_EQ(m.num_vertices(), 4);
  ASSERT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.F.row(1), (Eigen::RowVector3i(1, 3, 2)));
  EXPECT_EQ(m.V.row(3), (Eigen::RowVector3d(1, 1, 0)));
}

TEST(ReadStl, NegativeZeroMergesWithZero) {
  const std::string s =
      "solid z\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex -0 -0 0\nvertex 0 1 0\n"
      "vertex 0 0 1\nendloop\nendfacet\nendsolid z\n";
  const TriangleMesh m = read_stl_from_memory(s, "z.stl");
  EXPECT_EQ(m.num_vertices(), 4);
  EXPECT_EQ(m.F(1, 0), 0);
}

}  // namespace
}  // namespace breastfit::io
