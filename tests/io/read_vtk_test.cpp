#include "breastfit/io/read_vtk.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

#include "breastfit/core/errors.h"

namespace breastfit::io {
namespace {

template <typename T>
void put_be(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

std::string problem(std::string_view bytes, const std::string& name = "m.vtk") {
  try {
    read_vtk_from_memory(bytes, name);
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind(name + ": ", 0), 0u) << e.what();
    return e.problem();
  }
  ADD_FAILURE() << "no error for:\n" << bytes;
  return "";
}

double area(const TriangleMesh& m) {
  double a = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Vec3 p = m.V.row(m.F(f, 0)), q = m.V.row(m.F(f, 1)), r = m.V.row(m.F(f, 2));
    a += 0.5 * (q - p).cross(r - p).norm();
  }
  return a;
}

// Six points: a unit square (0..3) and two more for a strip (4, 5).
const char* kPoints = "POINTS 6 float\n0 0 0 1 0 0 1 1 0\n0 1 0 2 0 0 2 1 0\n";

TEST(ReadVtk, AsciiPolydataQuadTriangleAndStrip) {
  const std::string text = std::string("# vtk DataFile Version 3.0\nmy mesh\nASCII\nDATASET POLYDATA\n") + kPoints +
                           "VERTICES 1 2\n1 0\nLINES 1 3\n2 0 1\n"
                           "POLYGONS 2 9\n4 0 1 2 3\n3 0 1 2\nTRIANGLE_STRIPS 1 5\n4 1 4 2 5\n";
  const TriangleMesh m = read_vtk_from_memory(text, "m.vtk");
  ASSERT_EQ(m.num_vertices(), 6);
  ASSERT_EQ(m.num_faces(), 5);  // quad (2) + triangle + strip (2); vertices and lines dropped
  EXPECT_EQ(m.F.row(0), (Eigen::RowVector3i(0, 1, 2)));
  EXPECT_EQ(m.F.row(1), (Eigen::RowVector3i(0, 2, 3)));
  EXPECT_EQ(m.F.row(3), (Eigen::RowVector3i(1, 4, 2)));
  EXPECT_EQ(m.F.row(4), (Eigen::RowVector3i(2, 4, 5)));  // alternating winding
  EXPECT_EQ(m.V(5, 0), 2.0);
  EXPECT_FALSE(m.has_normals());
}

/// The same mesh in BINARY (big-endian), classic cell lists.
std::string binary_classic() {
  std::string s = "# vtk DataFile Version 3.0\nbinary\nBINARY\nDATASET POLYDATA\nPOINTS 6 double\n";
  const double p[18] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 2, 1, 0};
  for (double v : p) put_be(s, v);
  s += "\nPOLYGONS 2 9\n";
  for (std::int32_t v : {4, 0, 1, 2, 3, 3, 0, 1, 2}) put_be(s, v);
  s += "\nTRIANGLE_STRIPS 1 5\n";
  for (std::int32_t v : {4, 1, 4, 2, 5}) put_be(s, v);
  s += "\nPOINT_DATA 6\nNORMALS Normals float\n";
  for (int i = 0; i < 6; ++i)
    for (float v : {0.f, 0.f, 1.f}) put_be(s, v);
  s += "\nMETADATA\nINFORMATION 0\n\nSCALARS temperature float 1\nLOOKUP_TABLE default\n";
  for (int i = 0; i < 6; ++i) put_be(s, 20.5f);
  s += "\nCOLOR_SCALARS rgb 3\n";
  for (int i = 0; i < 18; ++i) s += static_cast<char>(10 * i);
  s += "\nCELL_DATA 3\nFIELD FieldData 1\nids 1 3 int\n";
  for (std::int32_t v : {7, 8, 9}) put_be(s, v);
  s += "\n";
  return s;
}

TEST(ReadVtk, BinaryBigEndianWithPointDataAndSkippedAttributes) {
  const TriangleMesh m = read_vtk_from_memory(binary_classic(), "b.vtk");
  ASSERT_EQ(m.num_vertices(), 6);
  ASSERT_EQ(m.num_faces(), 5);
  EXPECT_EQ(m.F.row(4), (Eigen::RowVector3i(2, 4, 5)));
  EXPECT_EQ(m.V(4, 0), 2.0);
  ASSERT_TRUE(m.has_normals());
  EXPECT_EQ(m.N(5, 2), 1.0);
  ASSERT_TRUE(m.has_colors());
  EXPECT_EQ(m.C(1, 0), 30);
  EXPECT_EQ(m.C(5, 2), 170);
}

TEST(ReadVtk, Version51OffsetsAndConnectivityAsciiAndBinary) {
  const std::string ascii = std::string("# vtk DataFile Version 5.1\nvtk output\nASCII\nDATASET POLYDATA\n") + kPoints +
                            "POLYGONS 3 7\nOFFSETS vtktypeint64\n0 4 7\nCONNECTIVITY vtktypeint64\n0 1 2 3 0 1 2\n"
                            "TRIANGLE_STRIPS 2 4\nOFFSETS vtktypeint64\n0 4\nCONNECTIVITY vtktypeint64\n1 4 2 5\n";
  const TriangleMesh a = read_vtk_from_memory(ascii, "a.vtk");
  ASSERT_EQ(a.num_faces(), 5);
  EXPECT_EQ(a.F.row(3), (Eigen::RowVector3i(1, 4, 2)));

  std::string b = "# vtk DataFile Version 5.1\nvtk output\nBINARY\nDATASET POLYDATA\nPOINTS 6 float\n";
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f, 2.f, 0.f, 0.f, 2.f, 1.f, 0.f}) put_be(b, v);
  b += "\nPOLYGONS 3 7\nOFFSETS vtktypeint64\n";
  for (std::int64_t v : {0, 4, 7}) put_be(b, v);
  b += "\nCONNECTIVITY vtktypeint64\n";
  for (std::int64_t v : {0, 1, 2, 3, 0, 1, 2}) put_be(b, v);
  b += "\n";
  const TriangleMesh m = read_vtk_from_memory(b, "b.vtk");
  ASSERT_EQ(m.num_faces(), 3);
  EXPECT_EQ(m.F, a.F.topRows(3));
  EXPECT_EQ(m.V, a.V);
}

TEST(ReadVtk, UnstructuredGridKeepsSurfaceCells) {
  const std::string text = std::string("# vtk DataFile Version 4.2\ngrid\nASCII\nDATASET UNSTRUCTURED_GRID\n") + kPoints +
                           "CELLS 5 22\n3 0 1 2\n4 0 1 3 2\n4 0 1 2 4\n2 4 5\n4 1 4 2 5\n"
                           "CELL_TYPES 5\n5\n8\n10\n3\n6\n";
  const TriangleMesh m = read_vtk_from_memory(text, "g.vtk");
  // triangle (1) + pixel 0 1 3 2 = square (2) + strip (2); tetra and line dropped.
  ASSERT_EQ(m.num_faces(), 5);
  EXPECT_EQ(m.F.row(1), (Eigen::RowVector3i(0, 1, 2)));
  EXPECT_EQ(m.F.row(2), (Eigen::RowVector3i(0, 2, 3)));
}

TEST(ReadVtk, VolumeOnlyGridIsRefusedClearly) {
  const std::string text = std::string("# vtk DataFile Version 4.2\ngrid\nASCII\nDATASET UNSTRUCTURED_GRID\n") + kPoints +
                           "CELLS 1 5\n4 0 1 2 4\nCELL_TYPES 1\n10\n";
  EXPECT_NE(problem(text).find("1 volume cells and no surface cells"), std::string::npos);
}

TEST(ReadVtk, ConcavePolygonIsEarClipped) {
  // An L-shaped hexagon (area 3): a fan from corner 0 would cover the notch.
  const std::string text =
      "# vtk DataFile Version 3.0\nL\nASCII\nDATASET POLYDATA\nPOINTS 6 float\n"
      "0 0 0 2 0 0 2 1 0 1 1 0 1 2 0 0 2 0\nPOLYGONS 1 7\n6 1 2 3 4 5 0\n";
  const TriangleMesh m = read_vtk_from_memory(text, "l.vtk");
  ASSERT_EQ(m.num_faces(), 4);
  EXPECT_NEAR(area(m), 3.0, 1e-12);
}

TEST(ReadVtk, SlicerRasHeaderIsConvertedToLps) {
  const std::string body = std::string("ASCII\nDATASET POLYDATA\n") + kPoints + "POLYGONS 1 4\n3 0 1 2\n"
                           "POINT_DATA 6\nNORMALS n float\n0 0 1 0 0 1 1 2 3 0 0 1 0 0 1 0 0 1\n";
  const TriangleMesh ras = read_vtk_from_memory("# vtk DataFile Version 3.0\n3D Slicer output. SPACE=RAS\n" + body, "r.vtk");
  const TriangleMesh lps = read_vtk_from_memory("# vtk DataFile Version 3.0\n3D Slicer output. SPACE=LPS\n" + body, "l.vtk");
  const TriangleMesh plain = read_vtk_from_memory("# vtk DataFile Version 3.0\nvtk output\n" + body, "p.vtk");
  EXPECT_EQ(lps.V, plain.V);
  EXPECT_EQ(ras.V(2, 0), -1.0);
  EXPECT_EQ(ras.V(2, 1), -1.0);
  EXPECT_EQ(ras.V(2, 2), 0.0);
  EXPECT_EQ(ras.N.row(2), (Eigen::RowVector3d(-1, -2, 3)));
  EXPECT_EQ(ras.F, plain.F);  // a rotation: the winding stays
}

TEST(ReadVtk, TextureCoordinatesAndFieldArraysWithStrings) {
  const std::string text = std::string("# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\n"
                                       "FIELD FieldData 2\nnames 1 2 string\nfirst%20name\nsecond\nNULL_ARRAY\n") +
                           kPoints + "POLYGONS 1 4\n3 0 1 2\nPOINT_DATA 6\n"
                                     "TEXTURE_COORDINATES tc 2 float\n0 0 1 0 1 1 0 1 0.5 0 0.5 1\n"
                                     "VECTORS v double\n0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n";
  const TriangleMesh m = read_vtk_from_memory(text, "t.vtk");
  ASSERT_TRUE(m.has_texcoords());
  EXPECT_EQ(m.UV(5, 1), 1.0);
  EXPECT_EQ(m.FUV, m.F);
}

TEST(ReadVtk, MalformedFilesGiveOneLineErrors) {
  const std::string head = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\n";
  EXPECT_EQ(problem(""), "empty file");
  EXPECT_NE(problem("ply\nformat ascii 1.0\n").find("not a legacy VTK file"), std::string::npos);
  EXPECT_NE(problem("# vtk DataFile Version 3.0\nt\nXML\n").find("unknown format 'XML'"), std::string::npos);
  EXPECT_NE(problem("# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n").find("not a surface mesh"),
            std::string::npos);
  EXPECT_NE(problem(head + kPoints + "POLYGONS 1 4\n3 0 1 9\n").find("POLYGONS cell 0 references point 9 but the file has 6 points"),
            std::string::npos);
  EXPECT_NE(problem(head + kPoints + "POLYGONS 2 4\n3 0 1 2\n").find("runs past"), std::string::npos);
  EXPECT_NE(problem(head + kPoints + "POLYGONS 1 5\n3 0 1 2 4\n").find("1 cells use 4 values but 5 are announced"),
            std::string::npos);
  EXPECT_NE(problem(head + "POINTS 2 float\n0 0 0 1 x 0\n").find("POINTS: bad value 'x'"), std::string::npos);
  EXPECT_NE(problem(head + "POINTS 2 float\n0 0 0 1 nan 0\n").find("point 1 has a non-finite coordinate"), std::string::npos);
  EXPECT_NE(problem(head + "POINTS 4000000000 float\n0 0 0\n").find("values announced but only"), std::string::npos);
  EXPECT_NE(problem(head + kPoints + "POLYHEDRA 1 2\n").find("unexpected keyword 'POLYHEDRA'"), std::string::npos);
  EXPECT_NE(problem(head + kPoints + "POLYGONS 2 7\nOFFSETS vtktypeint64\n0 4\nCONNECTIVITY vtktypeint64\n0 1 2 3 0 1 2\n")
                .find("the cell offsets end at 4 but the connectivity holds 7"),
            std::string::npos);
  EXPECT_NE(problem(head + "POLYGONS 1 4\n3 0 1 2\n").find("POLYGONS before POINTS"), std::string::npos);
  EXPECT_EQ(problem(head), "the file has no POINTS");
}

TEST(ReadVtk, EveryPrefixOfABinaryFileReadsOrFailsCleanly) {
  const std::string full = binary_classic();
  for (std::size_t n = 0; n < full.size(); ++n) {
    try {
      read_vtk_from_memory(std::string_view(full).substr(0, n), "p.vtk");
    } catch (const IoError&) {
    }
  }
  EXPECT_EQ(read_vtk_from_memory(full, "p.vtk").num_faces(), 5);
}

}  // namespace
}  // namespace breastfit::io
