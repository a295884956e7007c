#include "breastfit/io/write_ply.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/io/read_ply.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

/// Two triangles with coordinates that are not representable as float.
TriangleMesh sample_mesh() {
  TriangleMesh m;
  m.V.resize(4, 3);
  m.V << 0.1, 0.2, 0.3, 1.0 / 3.0, -2.5e-7, 1e10, 123.456789012345, 7, -0.0,
      std::numeric_limits<double>::min(), 5, 6;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 2, 3;
  m.N.resize(4, 3);
  m.N << 0, 0, 1, 0, 1, 0, 1, 0, 0, 0.6, 0.8, 0;
  m.C.resize(4, 3);
  m.C << 255, 0, 1, 2, 3, 4, 100, 150, 200, 7, 8, 9;
  return m;
}

TEST(WritePly, BinaryDoubleRoundTripIsExactWithNormalsAndColours) {
  const TriangleMesh m = sample_mesh();
  const TriangleMesh r = read_ply_from_memory(
      write_ply_to_memory(
          m, {.binary = true, .normals = true, .colors = true, .double_precision = true}),
      "rt.ply");
  EXPECT_EQ(r.V, m.V);
  EXPECT_EQ(r.F, m.F);
  EXPECT_EQ(r.N, m.N);
  EXPECT_EQ(r.C, m.C);
}

TEST(WritePly, AsciiDoubleRoundTripIsExact) {
  const TriangleMesh m = sample_mesh();
  const std::string text = write_ply_to_memory(
      m, {.binary = false, .normals = true, .colors = true, .double_precision = true});
  EXPECT_NE(text.find("format ascii 1.0"), std::string::npos);
  const TriangleMesh r = read_ply_from_memory(text, "rt.ply");
  EXPECT_EQ(r.V, m.V);
  EXPECT_EQ(r.F, m.F);
  EXPECT_EQ(r.N, m.N);
  EXPECT_EQ(r.C, m.C);
}

TEST(WritePly, DefaultBinaryStoresFloatAndRoundTripsFloatValuesExactly) {
  const TriangleMesh m = sample_mesh();
  const std::string bytes = write_ply_to_memory(m);
  EXPECT_NE(bytes.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_NE(bytes.find("property float x"), std::string::npos);
  EXPECT_EQ(bytes.find("nx"), std::string::npos) << "normals are off by default";
  const TriangleMesh r = read_ply_from_memory(bytes, "f.ply");
  EXPECT_EQ(r.V, m.V.cast<float>().cast<double>());
  EXPECT_FALSE(r.has_colors());
  // Float ascii also reads back exactly the float values.
  const TriangleMesh a = read_ply_from_memory(write_ply_to_memory(m, {.binary = false}), "a.ply");
  EXPECT_EQ(a.V, m.V.cast<float>().cast<double>());
}

TEST(WritePly, PointCloudHasNoFaceElementAndFileRoundTrips) {
  TriangleMesh m;
  m.V = Points::Random(5, 3);
  const auto path = test::temp_dir() / "cloud.ply";
  write_ply(path, m, {.double_precision = true});
  const TriangleMesh r = read_ply(path);
  EXPECT_TRUE(r.is_point_cloud());
  EXPECT_EQ(r.V, m.V);
}

TEST(WritePly, PerVertexTexcoordsWrittenAsUV) {
  TriangleMesh m = sample_mesh();
  m.UV = TexCoords::Random(4, 2);
  m.FUV = m.F;
  const TriangleMesh r =
      read_ply_from_memory(write_ply_to_memory(m, {.double_precision = true}), "uv.ply");
  ASSERT_TRUE(r.has_texcoords());
  EXPECT_EQ(r.UV, m.UV);
}

TEST(WritePly, InconsistentMeshIsInvalidInput) {
  TriangleMesh m = sample_mesh();
  m.F(1, 2) = 4;
  EXPECT_THROW(write_ply_to_memory(m), InvalidInput);
  m = sample_mesh();
  m.N.conservativeResize(3, 3);
  EXPECT_THROW(write_ply_to_memory(m), InvalidInput);
}

}  // namespace
}  // namespace breastfit::io
