#include "breastfit/io/io.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "breastfit/core/errors.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

TriangleMesh full_mesh() {
  TriangleMesh m;
  m.V.resize(4, 3);
  m.V << 0.1, 0.2, 0.3, 1.0 / 3.0, -2.5e-7, 1e10, 1, 1, 0, 0, 1, 2;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 2, 3;
  m.N.resize(4, 3);
  m.N << 0, 0, 1, 0, 0.6, 0.8, 0, 0, 1, 1.0 / 7.0, 0, 1;
  m.C.resize(4, 3);
  m.C << 0, 1, 2, 128, 254, 255, 3, 4, 5, 6, 7, 8;
  m.UV.resize(3, 2);
  m.UV << 0, 0, 1, 0.25, 0.5, 1;
  m.FUV.resize(2, 3);
  m.FUV << 0, 1, 2, 2, 1, 0;
  return m;
}

std::string message_of(const std::filesystem::path& path) {
  try {
    read_mesh(path);
  } catch (const IoError& e) {
    return e.what();
  }
  return "no IoError";
}

// One-line round trips, one per format and encoding.
TEST(Io, RoundTripPlyBinaryDoubleNormalsColours) {
  const auto p = test::temp_dir() / "m.ply";
  write_mesh(p, full_mesh(), {.normals = true, .colors = true, .double_precision = true});
  const TriangleMesh r = read_mesh(p);
  EXPECT_TRUE(r.V == full_mesh().V && r.F == full_mesh().F && r.N == full_mesh().N &&
              r.C == full_mesh().C);
}

TEST(Io, RoundTripPlyAsciiNormalsColours) {
  const auto p = test::temp_dir() / "m.PLY";
  write_mesh(p, full_mesh(),
             {.binary = false, .normals = true, .colors = true, .double_precision = true});
  const TriangleMesh r = read_mesh(p);
  EXPECT_TRUE(r.V == full_mesh().V && r.F == full_mesh().F && r.N == full_mesh().N &&
              r.C == full_mesh().C);
}

TEST(Io, RoundTripObjTexcoordsNormals) {
  const auto p = test::temp_dir() / "m.Obj";
  write_mesh(p, full_mesh(), {.normals = true});
  const TriangleMesh r = read_mesh(p);
  EXPECT_TRUE(r.V == full_mesh().V && r.F == full_mesh().F && r.N == full_mesh().N &&
              r.UV == full_mesh().UV && r.FUV == full_mesh().FUV);
}

TEST(Io, RoundTripStlAsciiAndBinary) {
  const auto dir = test::temp_dir();
  TriangleMesh m = full_mesh();
  m.V = m.V.cast<float>().cast<double>();  // STL stores float
  write_mesh(dir / "a.stl", m, {.binary = false});
  write_mesh(dir / "b.STL", m, {.binary = true});
  EXPECT_TRUE(read_mesh(dir / "a.stl").V == m.V && read_mesh(dir / "a.stl").F == m.F);
  EXPECT_TRUE(read_mesh(dir / "b.STL").V == m.V && read_mesh(dir / "b.STL").F == m.F);
}

TEST(Io, FixturesReadThroughTheFrontDoor) {
  EXPECT_EQ(read_mesh(test::data_dir() / "meshes" / "quad_ascii.ply").num_faces(), 3);
  EXPECT_EQ(read_mesh(test::data_dir() / "meshes" / "tetra.obj").num_faces(), 4);
  EXPECT_EQ(read_mesh(test::data_dir() / "meshes" / "tetra_ascii.stl").num_faces(), 4);
}

TEST(Io, UnknownExtensionMissingFileAndDirectory) {
  const auto dir = test::temp_dir();
  { std::ofstream(dir / "mesh.xyz") << "1 2 3\n"; }
  EXPECT_EQ(message_of(dir / "mesh.xyz"),
            (dir / "mesh.xyz").string() +
                ": unknown mesh extension '.xyz' (supported: .ply, .obj, .stl, .vtk, .vtp)");
  EXPECT_EQ(message_of(dir / "noext"),
            (dir / "noext").string() + ": no file extension (supported: .ply, .obj, .stl, .vtk, .vtp)");
  EXPECT_EQ(message_of(dir / "missing.ply"),
            (dir / "missing.ply").string() + ": file does not exist");
  std::filesystem::create_directories(dir / "folder.obj");
  EXPECT_EQ(message_of(dir / "folder.obj"),
            (dir / "folder.obj").string() + ": is a directory, not a mesh file");
  try {
    write_mesh(dir / "out.vtp", full_mesh());  // .vtp is read, not written
    ADD_FAILURE() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_EQ(e.problem(), "unknown mesh extension '.vtp' (supported: .ply, .obj, .stl, .vtk)");
  }
  EXPECT_THROW(write_mesh(dir / "out.off", full_mesh()), IoError);
  EXPECT_THROW(write_mesh(dir / "folder.obj", full_mesh()), IoError);
  EXPECT_THROW(write_mesh(dir / "no_such_dir" / "m.ply", full_mesh()), IoError);
}

}  // namespace
}  // namespace breastfit::io
