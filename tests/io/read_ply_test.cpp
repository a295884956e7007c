#include "breastfit/io/read_ply.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <string>
#include <vector>

#include "breastfit/core/errors.h"
#include "support/expect_same_mesh.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

template <typename T>
void put(std::string& out, T v, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

TEST(ReadPly, AsciiFixtureWithNormalsColoursQuadAndExtraElements) {
  const TriangleMesh m = read_ply(test::data_dir() / "meshes" / "quad_ascii.ply");
  ASSERT_EQ(m.num_vertices(), 5);
  ASSERT_EQ(m.num_faces(), 3);  // quad fan-triangulated + one triangle
  EXPECT_EQ(m.V(4, 2), 1.25);
  EXPECT_EQ(m.F.row(0), (Eigen::RowVector3i(0, 1, 2)));
  EXPECT_EQ(m.F.row(1), (Eigen::RowVector3i(0, 2, 3)));
  EXPECT_EQ(m.F.row(2), (Eigen::RowVector3i(0, 1, 4)));
  ASSERT_TRUE(m.has_normals());
  EXPECT_EQ(m.N(3, 2), 1.0);
  ASSERT_TRUE(m.has_colors());
  EXPECT_EQ(m.C(3, 0), 10);
  EXPECT_EQ(m.C(3, 2), 30);
  EXPECT_FALSE(m.has_texcoords());
}

TEST(ReadPly, VertexOnlyFileIsAPointCloud) {
  const TriangleMesh m = read_ply(test::data_dir() / "meshes" / "points.ply");
  ASSERT_EQ(m.num_vertices(), 3);
  EXPECT_TRUE(m.is_point_cloud());
  EXPECT_EQ(m.V(0, 0), 1.5);
  EXPECT_EQ(m.V(1, 2), 6e-3);
  EXPECT_EQ(m.V(2, 1), 8.25);
}

std::string binary_tetra(bool big_endian) {
  std::string s = "ply\r\nformat ";
  s += big_endian ? "binary_big_endian" : "binary_little_endian";
  s +=
      " 1.0\r\ncomment CRLF header\r\nelement vertex 4\r\nproperty double x\r\nproperty short y\r\n"
      "property float z\r\nproperty list ushort int8 junk\r\nproperty float red\r\n"
      "property float green\r\nproperty float blue\r\n"
      "element face 2\r\nproperty int tag\r\nproperty list int uint vertex_index\r\n"
      "element material 1\r\nproperty list uchar float values\r\nend_header\r\n";
  const double x[4] = {0.125, 1, 0, 0};
  const short y[4] = {0, 0, 1, -3};
  const float z[4] = {0, 0, 0, 1.5f};
  for (int i = 0; i < 4; ++i) {
    put(s, x[i], big_endian);
    put(s, y[i], big_endian);
    put(s, z[i], big_endian);
    put(s, static_cast<std::uint16_t>(2), big_endian);  // a list on the vertex, skipped
    put(s, static_cast<std::int8_t>(-1), big_endian);
    put(s, static_cast<std::int8_t>(5), big_endian);
    put(s, 1.0f, big_endian);  // float colours in [0,1]
    put(s, 0.5f, big_endian);
    put(s, 0.0f, big_endian);
  }
  put(s, 77, big_endian);
  put(s, 3, big_endian);
  for (std::uint32_t v : {0u, 1u, 2u}) put(s, v, big_endian);
  put(s, 78, big_endian);
  put(s, 4, big_endian);
  for (std::uint32_t v : {0u, 2u, 3u, 1u}) put(s, v, big_endian);
  put(s, static_cast<std::uint8_t>(1), big_endian);
  put(s, 9.0f, big_endian);
  return s;
}

TEST(ReadPly, BinaryLittleAndBigEndianWithMixedTypesAndSkippedLists) {
  for (bool big : {false, true}) {
    SCOPED_TRACE(big ? "big endian" : "little endian");
    const TriangleMesh m = read_ply_from_memory(binary_tetra(big), "tetra.ply");
    ASSERT_EQ(m.num_vertices(), 4);
    ASSERT_EQ(m.num_faces(), 3);
    EXPECT_EQ(m.V(0, 0), 0.125);
    EXPECT_EQ(m.V(3, 1), -3.0);
    EXPECT_EQ(m.V(3, 2), 1.5);
    EXPECT_EQ(m.F.row(1), (Eigen::RowVector3i(0, 2, 3)));
    EXPECT_EQ(m.F.row(2), (Eigen::RowVector3i(0, 3, 1)));
    ASSERT_TRUE(m.has_colors());
    EXPECT_EQ(m.C(2, 0), 255);
    EXPECT_EQ(m.C(2, 1), 128);
    EXPECT_EQ(m.C(2, 2), 0);
    EXPECT_FALSE(m.has_normals());
  }
}

TEST(ReadPly, FacesRepeatingAVertexAreDroppedZeroAreaKept) {
  const std::string s =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 3\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n2 0 0\n0 1 0\n"
      "3 0 1 1\n"     // repeated index: dropped
      "3 0 1 2\n"     // collinear (zero area): kept
      "4 0 1 3 3\n";  // quad with a repeat: only the valid fan triangle survives
  const TriangleMesh m = read_ply_from_memory(s, "deg.ply");
  ASSERT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.F.row(0), (Eigen::RowVector3i(0, 1, 2)));
  EXPECT_EQ(m.F.row(1), (Eigen::RowVector3i(0, 1, 3)));
}

/// The usual scanner layout (a vertex element of scalars, then a face element with only a
/// uchar/int index list), which little-endian files read through a direct path: `faces` are
/// written as given (count first). `extra` adds normals, colours and texture coordinates.
std::string scanner_ply(bool big_endian, const std::vector<std::vector<std::int32_t>>& faces,
                        bool extra, float bad_x = 0.0f) {
  std::string s = "ply\nformat ";
  s += big_endian ? "binary_big_endian" : "binary_little_endian";
  s += " 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n";
  if (extra) {
    s += "property double nx\nproperty double ny\nproperty double nz\nproperty uchar red\n"
         "property uchar green\nproperty uchar blue\nproperty float s\nproperty float t\n";
  }
  s += "element face " + std::to_string(faces.size()) +
       "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < 5; ++i) {
    put(s, i == 4 ? bad_x + 0.1f * static_cast<float>(i) : 0.1f * static_cast<float>(i), big_endian);
    put(s, 1.5f - static_cast<float>(i), big_endian);
    put(s, static_cast<float>(i * i) / 3.0f, big_endian);
    if (extra) {
      put(s, 0.0, big_endian);
      put(s, i == 2 ? -1.0 : 1.0, big_endian);
      put(s, 0.25 * i, big_endian);
      put(s, static_cast<std::uint8_t>(10 * i), big_endian);
      put(s, static_cast<std::uint8_t>(255 - i), big_endian);
      put(s, static_cast<std::uint8_t>(7), big_endian);
      put(s, 0.5f * static_cast<float>(i), big_endian);
      put(s, 1.0f / 3.0f, big_endian);
    }
  }
  for (const auto& f : faces) {
    put(s, static_cast<std::uint8_t>(f.size()), big_endian);
    for (std::int32_t v : f) put(s, v, big_endian);
  }
  return s;
}

TEST(ReadPly, ScannerLayoutReadsAsTheGeneralReaderDoes) {
  // Big-endian files take the general reader on this (little-endian) machine: the direct
  // path for the little-endian file must give the same mesh, bit for bit.
  const std::vector<std::vector<std::int32_t>> triangles = {{0, 1, 2}, {1, 3, 2}, {2, 2, 4}, {0, 4, 3}};
  for (bool extra : {false, true}) {
    SCOPED_TRACE(extra ? "normals, colours, texture coordinates" : "positions only");
    const TriangleMesh little = read_ply_from_memory(scanner_ply(false, triangles, extra), "l.ply");
    const TriangleMesh big = read_ply_from_memory(scanner_ply(true, triangles, extra), "b.ply");
    test::expect_same_mesh(little, big);
    ASSERT_EQ(little.num_faces(), 3);  // the face repeating vertex 2 is dropped
    EXPECT_EQ(little.F.row(2), (Eigen::RowVector3i(0, 4, 3)));
    EXPECT_EQ(little.V(1, 0), static_cast<double>(0.1f));
    EXPECT_EQ(little.has_normals(), extra);
    EXPECT_EQ(little.has_colors(), extra);
    EXPECT_EQ(little.has_texcoords(), extra);
  }
  // A quad among the triangles: read (and triangulated) by the general reader.
  const std::vector<std::vector<std::int32_t>> mixed = {{0, 1, 2}, {1, 3, 4, 2}};
  const TriangleMesh quad = read_ply_from_memory(scanner_ply(false, mixed, true), "q.ply");
  test::expect_same_mesh(quad, read_ply_from_memory(scanner_ply(true, mixed, true), "q.ply"));
  EXPECT_EQ(quad.num_faces(), 3);
}

TEST(ReadPly, ScannerLayoutErrorsAreTheGeneralReadersErrors) {
  const auto message = [](const std::string& bytes) {
    try {
      read_ply_from_memory(bytes, "scan.ply");
    } catch (const IoError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  for (const auto& faces : std::vector<std::vector<std::vector<std::int32_t>>>{
           {{0, 1, 5}}, {{0, -1, 2}}, {{0, 1}}}) {
    const std::string little = message(scanner_ply(false, faces, false));
    EXPECT_NE(little, "no error");
    EXPECT_EQ(little, message(scanner_ply(true, faces, false)));
  }
  const std::string nan_x = message(scanner_ply(false, {{0, 1, 2}}, false, std::nanf("")));
  EXPECT_NE(nan_x.find("non-finite"), std::string::npos) << nan_x;
  std::string truncated = scanner_ply(false, {{0, 1, 2}, {1, 3, 2}}, true);
  truncated.resize(truncated.size() - 5);
  const std::string cut = message(truncated);
  EXPECT_NE(cut.find("truncated"), std::string::npos) << cut;
}

/// Six vertices on a 2 x 3 grid; one strip 0 1 2 3 makes two triangles, the restart -1 separates
/// a second strip 2 3 4 5 5 whose repeated index makes a degenerate triangle to skip.
constexpr int kStrip[] = {0, 1, 2, 3, -1, 2, 3, 4, 5, 5};
const Eigen::RowVector3i kStripTriangles[] = {{0, 1, 2}, {2, 1, 3}, {2, 3, 4}, {4, 3, 5}};

void expect_strip_triangles(const TriangleMesh& m) {
  ASSERT_EQ(m.num_vertices(), 6);
  ASSERT_EQ(m.num_faces(), 4);
  for (int f = 0; f < 4; ++f) EXPECT_EQ(m.F.row(f), kStripTriangles[f]) << "triangle " << f;
}

TEST(ReadPly, AsciiTriangleStripsAreTriangulatedWithAlternatingWinding) {
  std::string s =
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
      "property float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n"
      "0 0 0\n0 1 0\n1 0 0\n1 1 0\n2 0 0\n2 1 0\n10";
  for (int i : kStrip) s += " " + std::to_string(i);
  s += "\n";
  expect_strip_triangles(read_ply_from_memory(s, "strip.ply"));
}

TEST(ReadPly, BinaryTriangleStripsAreTriangulated) {
  for (bool big : {false, true}) {
    SCOPED_TRACE(big ? "big endian" : "little endian");
    std::string s = "ply\nformat ";
    s += big ? "binary_big_endian" : "binary_little_endian";
    s +=
        " 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
        "element tristrips 1\nproperty list uint int vertex_indices\nend_header\n";
    for (int i = 0; i < 6; ++i) {
      put(s, static_cast<float>(i / 2), big);
      put(s, static_cast<float>(i % 2), big);
      put(s, 0.0f, big);
    }
    put(s, static_cast<std::uint32_t>(std::size(kStrip)), big);
    for (int i : kStrip) put(s, i, big);
    expect_strip_triangles(read_ply_from_memory(s, "strip.ply"));
  }
}

TEST(ReadPly, TriangleStripIndexOutOfRangeIsAnError) {
  const std::string s =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n"
      "0 0 0\n0 1 0\n1 0 0\n4 0 1 2 -2\n";
  EXPECT_THROW(read_ply_from_memory(s, "strip.ply"), IoError);
}

TEST(ReadPly, PerVertexTexcoordsAndNonFiniteNormalsDropped) {
  const std::string s =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
      "property float s\nproperty float t\nelement face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n0 0 0 nan 0 1 0 0\n1 0 0 0 0 1 1 0\n0 1 0 0 0 1 0 1\n3 0 1 2\n";
  const TriangleMesh m = read_ply_from_memory(s, "uv.ply");
  EXPECT_FALSE(m.has_normals());
  ASSERT_TRUE(m.has_texcoords());
  EXPECT_EQ(m.UV(2, 1), 1.0);
  EXPECT_EQ(m.FUV, m.F);
}

TEST(ReadPly, ConcaveFaceIsEarClippedAfterTheVertices) {
  // An L-shaped hexagon (area 3) in a face element listed before the vertices: its fan from
  // corner 0 would cover the notch (area 3.5 counted twice over).
  const std::string s =
      "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
      "element vertex 6\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
      "6 1 2 3 4 5 0\n0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n";
  const TriangleMesh m = read_ply_from_memory(s, "l.ply");
  ASSERT_EQ(m.num_faces(), 4);
  double area = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d p = m.V.row(m.F(f, 0)), q = m.V.row(m.F(f, 1)), r = m.V.row(m.F(f, 2));
    const Eigen::Vector3d n = (q - p).cross(r - p);
    EXPECT_GT(n.z(), 0) << "triangle " << f << " keeps the polygon's winding";
    area += 0.5 * n.norm();
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
}

}  // namespace
}  // namespace breastfit::io
