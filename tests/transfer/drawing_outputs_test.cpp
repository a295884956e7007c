#include "breastfit/transfer/drawing_outputs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
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

// write_scan_painted writes the colours and the scaled vertices without copying the whole scan:
// the same bytes as the painted copy scaled and written without its normals.
TEST(DrawingOutputs, PaintedScanIsThePaintedCopyScaledAndWritten) {
  TriangleMesh scan = grid();
  scan.N = Points::Constant(scan.num_vertices(), 3, 0.0);
  scan.N.col(2).setOnes();
  const double from_mm = 0.001;
  EXPECT_TRUE(paint_colors(scan, sample_curves()) == paint_drawings(scan, sample_curves()).C);
  TriangleMesh expected = paint_drawings(scan, sample_curves());
  expected.V *= from_mm;
  expected.N.resize(0, 3);
  io::MeshWriteOptions wo;
  wo.colors = true;
  const auto dir = test::temp_dir();
  io::write_mesh(dir / "expected.ply", expected, wo);
  write_scan_painted(dir / "painted.ply", scan, sample_curves(), from_mm);
  auto bytes = [](const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(bytes(dir / "painted.ply"), bytes(dir / "expected.ply"));
  EXPECT_THROW(paint_colors(scan, sample_curves(), PaintOptions{.width_mm = -1}), InvalidInput);
}

// Distance from q to the polyline (closed: with the last segment back to the start).
double polyline_distance(const Points& P, bool closed, const Vec3& q) {
  double best = std::numeric_limits<double>::infinity();
  const Index n = P.rows();
  for (Index i = 0; i + 1 < n + (closed ? 1 : 0); ++i) {
    const Vec3 a = P.row(i).transpose(), b = P.row((i + 1) % n).transpose();
    const double t = std::clamp((q - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-300), 0.0, 1.0);
    best = std::min(best, (a + t * (b - a) - q).norm());
  }
  return best;
}

// Points scattered in 3D around the curves (off the coarse grid's cells and across their
// borders): painted exactly when near a curve, whatever cell they fall in.
TEST(DrawingOutputs, PaintsEveryPointNearACurveAndNoFarOne) {
  const auto curves = sample_curves();
  TriangleMesh cloud;
  const int n = 20000;
  cloud.V.resize(n, 3);
  std::uint64_t state = 12345;
  const auto uniform = [&state](double lo, double hi) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  for (int i = 0; i < n; ++i) {
    if (i % 4 == 0) {  // anywhere around the curves
      cloud.V.row(i) << uniform(-40, 110), uniform(-40, 40), uniform(-5, 110);
    } else {  // within a few mm of a curve point (the band's edge, across grid cells)
      const Points& P = curves[i % 2].points;
      const Index k = static_cast<Index>(uniform(0, static_cast<double>(P.rows()) - 1e-9));
      cloud.V.row(i) = P.row(k) + Eigen::RowVector3d(uniform(-5, 5), uniform(-5, 5), uniform(-5, 5));
    }
  }
  cloud.F.resize(1, 3);
  cloud.F << 0, 1, 2;
  PaintOptions o;
  o.width_mm = 3.0;
  const TriangleMesh painted = paint_drawings(cloud, curves, o);
  int near = 0;
  for (Index v = 0; v < n; ++v) {
    const Vec3 q = cloud.V.row(v).transpose();
    double d = std::numeric_limits<double>::infinity();
    for (const auto& c : curves) d = std::min(d, polyline_distance(c.points, c.closed, q));
    const bool skin = painted.C(v, 0) == o.skin[0] && painted.C(v, 1) == o.skin[1] && painted.C(v, 2) == o.skin[2];
    if (d <= 0.5 * o.width_mm) {
      EXPECT_FALSE(skin) << "vertex " << v << " at " << d << " mm";
      ++near;
    }
    if (d > 0.5 * o.width_mm + 0.5) EXPECT_TRUE(skin) << "vertex " << v << " at " << d << " mm";
  }
  EXPECT_GT(near, 1000);
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
