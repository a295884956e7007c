// End-to-end tests of `breastfit inspect` through the built executable.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>

#include "breastfit/io/io.h"
#include "breastfit/io/markups.h"
#include "support/read_json.h"
#include "support/test_paths.h"

namespace breastfit {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// n x n grid of h-sized squares (z = 0) with the square (1, 1) removed: one outer border and one
/// hole; plus a separate triangle far above (a second component).
TriangleMesh holey_grid(int n, double h) {
  TriangleMesh g;
  const int nv = (n + 1) * (n + 1);
  g.V.resize(nv + 3, 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) g.V.row(j * (n + 1) + i) << i * h, j * h, 0.0;
  g.V.row(nv) << 0, 0, 10 * h;
  g.V.row(nv + 1) << h, 0, 10 * h;
  g.V.row(nv + 2) << 0, h, 10 * h;
  std::vector<Eigen::Matrix<Index, 1, 3>> tris;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i == 1 && j == 1) continue;
      const Index a = j * (n + 1) + i, b = a + 1, c = a + (n + 1), d = c + 1;
      tris.push_back({a, b, d});
      tris.push_back({a, d, c});
    }
  tris.push_back({nv, nv + 1, nv + 2});
  g.F.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t f = 0; f < tris.size(); ++f) g.F.row(static_cast<Eigen::Index>(f)) = tris[f];
  return g;
}


TEST(InspectCommand, MeshTextAndJson) {
  ASSERT_FALSE(test::cli_path().empty());
  const fs::path p = test::temp_dir() / "grid.ply";
  io::write_mesh(p, holey_grid(4, 40.0));
  std::string out;
  ASSERT_EQ(test::run_cli("inspect '" + p.string() + "'", &out), 0) << out;
  EXPECT_NE(out.find("vertices: 28"), std::string::npos) << out;
  EXPECT_NE(out.find("components: 2"), std::string::npos) << out;
  EXPECT_NE(out.find("units: mm"), std::string::npos) << out;

  const json j = test::run_cli_json("inspect --json '" + p.string() + "'");
  EXPECT_EQ(j["kind"], "mesh");
  EXPECT_EQ(j["num_vertices"], 28);
  EXPECT_EQ(j["num_faces"], 31);
  EXPECT_EQ(j["components"]["count"], 2);
  EXPECT_EQ(j["components"]["face_counts"], json::array({30, 1}));
  EXPECT_EQ(j["boundary"]["num_loops"], 3);
  EXPECT_NEAR(j["boundary"]["loops"][0]["length"].get<double>(), 640.0, 1e-3);
  EXPECT_NEAR(j["boundary"]["loops"][1]["length"].get<double>(), 160.0, 1e-3);
  EXPECT_NEAR(j["edge_length"]["min"].get<double>(), 40.0, 1e-4);
  EXPECT_NEAR(j["edge_length"]["median"].get<double>(), 40.0, 1e-4);
  EXPECT_EQ(j["num_degenerate_faces"], 0);
  EXPECT_EQ(j["num_non_manifold_edges"], 0);
  EXPECT_EQ(j["units"], "mm");
  EXPECT_EQ(j["units_source"], "guessed");
  EXPECT_NEAR(j["max_extent_mm"].get<double>(), 400.0, 1e-3);
  EXPECT_NEAR(j["bbox"]["max"][2].get<double>(), 400.0, 1e-3);
}

TEST(InspectCommand, MetreMeshAndForcedUnits) {
  const fs::path p = test::temp_dir() / "grid_m.obj";
  io::write_mesh(p, holey_grid(4, 0.1));  // 0.4 m across, 1 m tall
  json j = test::run_cli_json("inspect --json '" + p.string() + "'");
  EXPECT_EQ(j["units"], "m");
  EXPECT_NEAR(j["max_extent_mm"].get<double>(), 1000.0, 1e-3);
  j = test::run_cli_json("inspect --json --units mm '" + p.string() + "'");
  EXPECT_EQ(j["units"], "mm");
  EXPECT_EQ(j["units_source"], "given");
  // Ambiguous extent (20 units): no guess, the reason is reported, still exit 0.
  const fs::path q = test::temp_dir() / "small.ply";
  io::write_mesh(q, holey_grid(2, 2.0));
  j = test::run_cli_json("inspect --json '" + q.string() + "'");
  EXPECT_TRUE(j["units"].is_null());
  EXPECT_NE(j["units_problem"].get<std::string>().find("pass --units"), std::string::npos);
}

TEST(InspectCommand, PointCloud) {
  TriangleMesh cloud;
  cloud.V.resize(4, 3);
  cloud.V << 0, 0, 0, 300, 0, 0, 0, 200, 0, 0, 0, 100;
  const fs::path p = test::temp_dir() / "cloud.ply";
  io::write_mesh(p, cloud);
  const json j = test::run_cli_json("inspect --json '" + p.string() + "'");
  EXPECT_EQ(j["kind"], "point_cloud");
  EXPECT_EQ(j["num_vertices"], 4);
  EXPECT_EQ(j["num_faces"], 0);
  EXPECT_TRUE(j["edge_length"].is_null());
  EXPECT_EQ(j["units"], "mm");
  std::string out;
  EXPECT_EQ(test::run_cli("inspect '" + p.string() + "'", &out), 0);
  EXPECT_NE(out.find("kind: point cloud"), std::string::npos) << out;
}

TEST(InspectCommand, MarkupsWithPointsAndCurves) {
  Markups m;
  m.points = {{"nipple_L", Vec3(1, 2, 3)}, {"mystery", Vec3(4, 5, 6)}};
  Curve c;
  c.name = "breast_contour_L";
  c.closed = true;
  c.points.resize(4, 3);
  c.points << 10, 0, 0, 0, 10, 0, -10, 0, 0, 0, -10, 0;
  m.curves.push_back(c);
  const fs::path p = test::temp_dir() / "drawings.mrk.json";
  io::write_markups(p, m, {.units = "m"});
  const json j = test::run_cli_json("inspect --json '" + p.string() + "'");
  EXPECT_EQ(j["kind"], "markups");
  EXPECT_EQ(j["declared_units"], "m");
  EXPECT_EQ(j["units"], "mm");
  ASSERT_EQ(j["points"].size(), 2u);
  EXPECT_EQ(j["points"][0]["name"], "nipple_L");
  EXPECT_NEAR(j["points"][0]["position"][2].get<double>(), 3.0, 1e-9);
  EXPECT_EQ(j["points"][1]["known"], false);
  EXPECT_EQ(j["unknown_names"], json::array({"mystery"}));
  EXPECT_EQ(j["missing_landmarks"].size(), 11u);
  ASSERT_EQ(j["curves"].size(), 1u);
  EXPECT_EQ(j["curves"][0]["closed"], true);
  EXPECT_EQ(j["curves"][0]["num_points"], 4);
  EXPECT_NEAR(j["curves"][0]["length"].get<double>(), 40 * std::sqrt(2.0), 1e-6);
  std::string out;
  EXPECT_EQ(test::run_cli("inspect '" + p.string() + "'", &out), 0);
  EXPECT_NE(out.find("breast_contour_L  closed, 4 points"), std::string::npos) << out;
  EXPECT_NE(out.find("mystery"), std::string::npos) << out;
  // The same content under a plain .json name is still recognised as markups (curves kept).
  const fs::path q = p.parent_path() / "drawings.json";  // (temp_dir() would empty the directory)
  fs::copy_file(p, q);
  const json k = test::run_cli_json("inspect --json '" + q.string() + "'");
  EXPECT_EQ(k["kind"], "markups");
  EXPECT_EQ(k["curves"].size(), 1u);
}

TEST(InspectCommand, SkippedMarkupTypesAndUnplacedPointsAreWarnedAbout) {
  const fs::path p = test::temp_dir() / "mixed.mrk.json";
  std::ofstream(p) << R"({"markups": [
    {"type": "Fiducial", "name": "F", "controlPoints": [{"label": "xiphoid", "position": [1, 2, 3]},
       {"label": "nipple_R", "position": "", "positionStatus": "missing"}]},
    {"type": "Plane", "name": "midline", "controlPoints": [{"position": [0, 0, 0]}]}]})";
  std::string out;
  EXPECT_EQ(test::run_cli("inspect '" + p.string() + "'", &out), 0) << out;
  EXPECT_NE(out.find("breastfit: warning: " + p.string() + ": markup 'midline' of type Plane skipped"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("breastfit: warning: " + p.string() + ": markup 'F' control point 'nipple_R' skipped"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("points: 1"), std::string::npos) << out;
}

TEST(InspectCommand, CsvLandmarksWithUnits) {
  const fs::path p = test::temp_dir() / "lm.csv";
  std::ofstream(p) << "name,x,y,z\nxiphoid,0.1,0.2,0.3\nnipple_R,0.4,0.5,0.6\n";
  json j = test::run_cli_json("inspect --json '" + p.string() + "'");
  EXPECT_EQ(j["kind"], "landmarks");
  EXPECT_TRUE(j["declared_units"].is_null());
  EXPECT_EQ(j["units"], "file units");
  EXPECT_NEAR(j["points"][1]["position"][0].get<double>(), 0.4, 1e-12);
  j = test::run_cli_json("inspect --json --units m '" + p.string() + "'");
  EXPECT_EQ(j["units"], "mm");
  EXPECT_NEAR(j["points"][1]["position"][0].get<double>(), 400.0, 1e-9);
}

TEST(InspectCommand, BadFilesFailWithOneLineNamingTheFile) {
  const fs::path dir = test::temp_dir();
  const fs::path junk = dir / "junk.ply";
  std::ofstream(junk) << "this is not a ply file\n";
  const fs::path bad_json = dir / "bad.mrk.json";
  std::ofstream(bad_json) << "{\"markups\": [";
  const fs::path nan_csv = dir / "nan.csv";
  std::ofstream(nan_csv) << "xiphoid,1,nan,3\n";
  for (const fs::path& p : {junk, bad_json, nan_csv, dir / "missing.stl"}) {
    std::string out;
    const int rc = test::run_cli("inspect '" + p.string() + "'", &out);
    EXPECT_EQ(rc, 4) << p << ": " << out;
    EXPECT_NE(out.find(p.filename().string()), std::string::npos) << out;
    EXPECT_NE(out.find("breastfit: error: "), std::string::npos) << out;
    // One line: a single trailing newline.
    EXPECT_EQ(out.find('\n'), out.size() - 1) << out;
  }
  std::string out;
  EXPECT_EQ(test::run_cli("inspect --units cm '" + junk.string() + "'", &out), 2) << out;
  // An unknown extension lists what inspect reads: meshes and landmark files.
  const fs::path txt = dir / "points.txt";
  std::ofstream(txt) << "xiphoid 1 2 3\n";
  EXPECT_EQ(test::run_cli("inspect '" + txt.string() + "'", &out), 4) << out;
  EXPECT_NE(out.find("unknown extension '.txt' (supported: meshes .ply, .obj, .stl, .vtk, .vtp; landmarks and markups "
                     ".mrk.json, .json, .csv, .fcsv)"),
            std::string::npos)
      << out;
}

}  // namespace
}  // namespace breastfit
