#include "breastfit/transfer/drawing_outputs.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/io/markups.h"
#include "support/grid_mesh.h"
#include "support/test_paths.h"

namespace breastfit::transfer {
namespace {

std::vector<TransferredCurve> sample_curves() {
  TransferredCurve loop;
  loop.name = "breast_contour_R";
  loop.closed = true;
  loop.points.resize(40, 3);
  for (int i = 0; i < 40; ++i) loop.points.row(i) << 30 * std::cos(2 * M_PI * i / 40), 30 * std::sin(2 * M_PI * i / 40), 5.0;
  loop.supported.assign(40, true);
  TransferredCurve line;
  line.name = "sternum";
  line.points.resize(11, 3);
  for (int i = 0; i < 11; ++i) line.points.row(i) << 100.0, 0.0, 10.0 * i;
  line.supported.assign(11, true);
  return {loop, line};
}

// A flat grid 200 x 200 mm, 2 mm spacing, z = 5 (the loop lies on it).
TriangleMesh grid() { return test::grid_mesh(50, 2.0, [](double, double) { return 5.0; }); }

TEST(DrawingOutputs, PlyHasVerticesAndEdgesPerCurve) {
  const auto path = test::temp_dir() / "drawings.ply";
  write_drawings_ply(path, sample_curves(), 0.001);
  std::ifstream f(path);
  std::string line;
  long nv = -1, ne = -1;
  std::vector<std::string> header;
  while (std::getline(f, line) && line != "end_header") {
    header.push_back(line);
    std::istringstream ss(line);
    std::string a, b;
    long n;
    if (ss >> a >> b >> n && a == "element") (b == "vertex" ? nv : ne) = n;
  }
  ASSERT_EQ(line, "end_header");
  EXPECT_EQ(header[0], "ply");
  EXPECT_EQ(nv, 51);
  EXPECT_EQ(ne, 40 + 10);  // closed loop: 40 edges; open line: 10
  std::vector<Vec3> V;
  for (long i = 0; i < nv; ++i) {
    double x, y, z;
    int r, g, b;
    ASSERT_TRUE(f >> x >> y >> z >> r >> g >> b);
    V.emplace_back(x, y, z);
  }
  EXPECT_NEAR(V[0].x(), 0.030, 1e-12);  // converted to metres
  EXPECT_NEAR(V[50].z(), 0.100, 1e-12);
  std::vector<std::pair<int, int>> E;
  for (long i = 0; i < ne; ++i) {
    int a, b;
    ASSERT_TRUE(f >> a >> b);
    ASSERT_GE(a, 0);
    ASSERT_LT(b, nv);
    E.emplace_back(a, b);
  }
  EXPECT_EQ(E[39], std::make_pair(39, 0));   // closing edge of the loop
  EXPECT_EQ(E[40], std::make_pair(40, 41));  // the sternum starts after the loop
  int extra;
  EXPECT_FALSE(f >> extra);
  EXPECT_THROW(write_drawings_ply(path, sample_curves(), 0.0), InvalidInput);
  EXPECT_THROW(write_drawings_ply(test::temp_dir() / "no" / "such" / "dir.ply", sample_curves()), IoError);
}

TEST(DrawingOutputs, ObjHasOneLinePerCurve) {
  const auto path = test::temp_dir() / "drawings.obj";
  write_drawings_obj(path, sample_curves());
  std::ifstream f(path);
  std::string line;
  int nv = 0;
  std::vector<std::vector<int>> lines;
  std::vector<std::string> objects;
  while (std::getline(f, line)) {
    std::istringstream ss(line);
    std::string tag;
    ss >> tag;
    if (tag == "v") ++nv;
    if (tag == "o") objects.emplace_back(line.substr(2));
    if (tag == "l") {
      lines.emplace_back();
      int i;
      while (ss >> i) lines.back().push_back(i);
    }
  }
  EXPECT_EQ(nv, 51);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(objects, (std::vector<std::string>{"breast_contour_R", "sternum"}));
  EXPECT_EQ(lines[0].size(), 41u);  // closed: first index repeated
  EXPECT_EQ(lines[0].front(), 1);
  EXPECT_EQ(lines[0].back(), 1);
  EXPECT_EQ(lines[1].front(), 41);
  EXPECT_EQ(lines[1].back(), 51);
}

TEST(DrawingOutputs, PaintedScanColoursABandAroundTheCurves) {
  const TriangleMesh scan = grid();
  PaintOptions o;
  o.width_mm = 4.0;
  const TriangleMesh painted = paint_drawings(scan, sample_curves(), o);
  ASSERT_TRUE(painted.has_colors());
  const Rgb blue = drawing_color("breast_contour_R");
  int on = 0;
  for (Index v = 0; v < scan.num_vertices(); ++v) {
    const double r = scan.V.row(v).head<2>().norm();
    const bool is_blue = painted.C(v, 0) == blue[0] && painted.C(v, 1) == blue[1] && painted.C(v, 2) == blue[2];
    if (std::abs(r - 30.0) < 1.0) {
      EXPECT_TRUE(is_blue) << "vertex at r = " << r;
      ++on;
    }
    if (std::abs(r - 30.0) > 3.0) {
      EXPECT_FALSE(is_blue) << "vertex at r = " << r;
    }
  }
  EXPECT_GT(on, 50);

  const auto path = test::temp_dir() / "scan_painted.ply";
  write_scan_painted(path, scan, sample_curves(), 0.001, o);
  const TriangleMesh back = io::read_mesh(path);
  ASSERT_EQ(back.num_vertices(), scan.num_vertices());
  ASSERT_EQ(back.num_faces(), scan.num_faces());
  ASSERT_TRUE(back.has_colors());
  EXPECT_TRUE(back.C == painted.C);
  EXPECT_NEAR(back.V(0, 0), -0.1, 1e-6);
  EXPECT_THROW(paint_drawings(scan, sample_curves(), PaintOptions{.width_mm = 0}), InvalidInput);
}

TEST(DrawingOutputs, MarkupsOfTransferredCurvesLoadBackIdentically) {
  const auto curves = sample_curves();
  const Markups m = to_markups(curves);
  const auto path = test::temp_dir() / "drawings.mrk.json";
  io::write_markups(path, m, {.units = "mm"});
  const Markups back = io::read_markups(path);
  ASSERT_EQ(back.curves.size(), m.curves.size());
  for (size_t i = 0; i < m.curves.size(); ++i) {
    EXPECT_EQ(back.curves[i].name, m.curves[i].name);
    EXPECT_EQ(back.curves[i].closed, m.curves[i].closed);
    ASSERT_EQ(back.curves[i].points.rows(), m.curves[i].points.rows());
    EXPECT_LT((back.curves[i].points - m.curves[i].points).cwiseAbs().maxCoeff(), 1e-9);
  }
  // in metres, read back as mm
  io::write_markups(path, m, {.units = "m"});
  const Markups back_m = io::read_markups(path);
  EXPECT_LT((back_m.curves[0].points - m.curves[0].points).cwiseAbs().maxCoeff(), 1e-6);
}

}  // namespace
}  // namespace breastfit::transfer

namespace breastfit::transfer {
namespace {

TEST(DrawingOutputs, LaterCurvesArePaintedOnTop) {
  const TriangleMesh scan = grid();
  auto curves = sample_curves();
  TransferredCurve fold = curves[0];  // the same loop drawn again as a fold
  fold.name = "imf_R";
  curves.push_back(fold);
  const TriangleMesh painted = paint_drawings(scan, curves);
  const Rgb green = drawing_color("imf_R"), blue = drawing_color("breast_contour_R");
  int n_green = 0, n_blue = 0;
  for (Index v = 0; v < scan.num_vertices(); ++v) {
    n_green += painted.C(v, 0) == green[0] && painted.C(v, 1) == green[1] && painted.C(v, 2) == green[2];
    n_blue += painted.C(v, 0) == blue[0] && painted.C(v, 1) == blue[1] && painted.C(v, 2) == blue[2];
  }
  EXPECT_GT(n_green, 50);
  EXPECT_EQ(n_blue, 0);
}

}  // namespace
}  // namespace breastfit::transfer
