#include "breastfit/io/write_vtk.h"

#include <gtest/gtest.h>

#include <string>

#include "breastfit/io/io.h"
#include "breastfit/io/read_vtk.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

TriangleMesh test_mesh() {
  TriangleMesh m;
  m.V.resize(4, 3);
  m.V << 0.1, 0.2, 0.3, 1.0 / 3.0, 0, 0, 0, 1e-7, 0, 0, 0, 12345.678;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 2, 3;
  m.N.resize(4, 3);
  m.N << 0, 0, 1, 0, 1, 0, 1, 0, 0, 0, 0, -1;
  m.C.resize(4, 3);
  m.C << 0, 1, 2, 253, 254, 255, 10, 20, 30, 40, 50, 60;
  m.UV.resize(4, 2);
  m.UV << 0, 0, 1, 0, 1, 1, 0, 1;
  m.FUV = m.F;
  return m;
}

TEST(WriteVtk, RoundTripsBinaryAndAsciiInDoubleAndFloat) {
  const TriangleMesh m = test_mesh();
  for (bool binary : {true, false}) {
    for (bool dbl : {true, false}) {
      SCOPED_TRACE(std::string(binary ? "binary" : "ascii") + (dbl ? " double" : " float"));
      MeshWriteOptions o{.binary = binary, .normals = true, .colors = true, .texcoords = true, .double_precision = dbl};
      const std::string bytes = write_vtk_to_memory(m, o);
      EXPECT_EQ(bytes.rfind("# vtk DataFile Version 3.0\nbreastfit SPACE=LPS\n", 0), 0u);
      const TriangleMesh r = read_vtk_from_memory(bytes, "r.vtk");
      EXPECT_EQ(r.F, m.F);
      if (dbl) {
        EXPECT_EQ(r.V, m.V);
      } else {
        EXPECT_EQ(r.V, m.V.cast<float>().cast<double>());
      }
      EXPECT_EQ(r.N, m.N);
      EXPECT_EQ(r.C, m.C);
      EXPECT_EQ(r.UV, m.UV);
    }
  }
}

TEST(WriteVtk, PointCloudAndFrontDoor) {
  TriangleMesh cloud;
  cloud.V = test_mesh().V;
  const std::string bytes = write_vtk_to_memory(cloud, {.binary = false});
  EXPECT_EQ(bytes.find("POLYGONS"), std::string::npos);
  EXPECT_TRUE(read_vtk_from_memory(bytes, "c.vtk").is_point_cloud());

  const auto path = test::temp_dir() / "m.VTK";  // the extension is case-insensitive
  write_mesh(path, test_mesh());
  const TriangleMesh r = read_mesh(path);
  EXPECT_EQ(r.F, test_mesh().F);
  EXPECT_FALSE(r.has_normals());  // MeshWriteOptions' default: no normals
}

}  // namespace
}  // namespace breastfit::io
