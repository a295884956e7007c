#include "breastfit/io/write_obj.h"

#include <gtest/gtest.h>

#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/io/read_obj.h"
#include "support/expect_same_mesh.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

TriangleMesh textured_quad() {
  TriangleMesh m;
  m.V.resize(4, 3);
  m.V << 0.1, 0.2, 0.3, 1.0 / 3.0, -2.5e-7, 1e10, 1, 1, 0, 0, 1, -0.0;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 2, 3;
  m.N.resize(4, 3);
  m.N << 0, 0, 1, 0, 0.6, 0.8, 0, 0, 1, 1.0 / 7.0, 0, 1;
  m.UV.resize(5, 2);
  m.UV << 0, 0, 1, 0, 1, 1, 0, 1, 0.123456789, 0.5;
  m.FUV.resize(2, 3);
  m.FUV << 0, 1, 2, 4, 2, 3;
  m.C.resize(4, 3);
  m.C << 0, 1, 2, 128, 254, 255, 3, 4, 5, 6, 7, 8;
  return m;
}

TEST(WriteObj, RoundTripWithTexcoordsNormalsAndColoursIsExact) {
  const TriangleMesh m = textured_quad();
  const TriangleMesh r = read_obj_from_memory(
      write_obj_to_memory(m, {.normals = true, .colors = true, .texcoords = true}), "rt.obj");
  test::expect_same_mesh(r, m);
}

TEST(WriteObj, OptionsSelectWhatIsWritten) {
  const TriangleMesh m = textured_quad();
  const std::string text = write_obj_to_memory(m, {.texcoords = false});
  EXPECT_EQ(text.find("vt "), std::string::npos);
  EXPECT_EQ(text.find("vn "), std::string::npos);
  EXPECT_NE(text.find("f 1 2 3\n"), std::string::npos);
  const std::string normals_only = write_obj_to_memory(m, {.normals = true, .texcoords = false});
  EXPECT_NE(normals_only.find("f 1//1 2//2 3//3\n"), std::string::npos);
}

TEST(WriteObj, FileRoundTrip) {
  const TriangleMesh m = textured_quad();
  const auto path = test::temp_dir() / "quad.obj";
  write_obj(path, m);
  const TriangleMesh r = read_obj(path);
  EXPECT_EQ(r.V, m.V);
  EXPECT_EQ(r.FUV, m.FUV);
}

}  // namespace
}  // namespace breastfit::io
