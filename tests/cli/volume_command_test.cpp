// `breastfit volume` end to end on a synthetic surface: a Gaussian bump on a plane with a closed
// curve around it (volume known exactly), in mm and in metres, and its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "breastfit/io/io.h"
#include "breastfit/io/markups.h"
#include "breastfit/synth/synth_case.h"
#include "support/default_template.h"
#include "support/grid_mesh.h"
#include "support/read_json.h"
#include "support/test_paths.h"

namespace breastfit {
namespace {

namespace fs = std::filesystem;

// A Gaussian bump (height kA, width kS) centred at (5, 0) on a flat grid, cut by a circle of
// radius kC: the membrane spanning the circle is the plane z = f(kC), so the volume is
// ∫∫ (f − f(kC)) over the disc = 2π kA kS² (1 − e) − π kC² kA e with e = exp(−kC² / 2kS²).
constexpr double kA = 20, kS = 15, kC = 35;

double bump(double x, double y) { return kA * std::exp(-((x - 5) * (x - 5) + y * y) / (2 * kS * kS)); }
double cap_volume_ml() {
  const double e = std::exp(-kC * kC / (2 * kS * kS));
  return (2 * M_PI * kA * kS * kS * (1 - e) - M_PI * kC * kC * kA * e) / 1000.0;
}

TriangleMesh cap_mesh() { return test::grid_mesh(40, 2.0, bump); }

Markups cap_markups() {
  Markups m;
  Curve base{"cap", true, Points(360, 3)};
  for (int i = 0; i < 360; ++i) {
    const double x = 5 + kC * std::cos(i * M_PI / 180), y = kC * std::sin(i * M_PI / 180);
    base.points.row(i) << x, y, bump(x, y);
  }
  Curve small{"small", true, Points(100, 3)};
  for (int i = 0; i < 100; ++i) {
    const double x = -50 + 8 * std::cos(i * 2 * M_PI / 100), y = 50 + 8 * std::sin(i * 2 * M_PI / 100);
    small.points.row(i) << x, y, bump(x, y);  // nearly flat there: volume ~0
  }
  Curve open{"line", false, Points(3, 3)};
  open.points << -60, -60, 0, -50, -60, 0, -50, -50, 0;
  m.curves = {base, small, open};
  m.points.push_back({"nipple_R", Vec3(5, 0, kA)});
  return m;
}

using test::run_cli_json;

TEST(VolumeCommand, MeasuresClosedCurvesInAnyUnits) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  io::write_mesh(dir / "cap.ply", cap_mesh());
  io::write_markups(dir / "curves.mrk.json", cap_markups());

  std::string out;
  const std::string on_cap = "volume " + (dir / "cap.ply").string() + " --curves " + (dir / "curves.mrk.json").string();
  ASSERT_EQ(test::run_cli(on_cap, &out), 0) << out;  // the table
  EXPECT_NE(out.find("volume_ml"), std::string::npos) << out;
  EXPECT_NE(out.find("cap"), std::string::npos) << out;
  EXPECT_EQ(out.find("line"), std::string::npos) << out;  // open curves are not measured
  const nlohmann::json j = run_cli_json(on_cap + " --json --regions");
  ASSERT_EQ(j["curves"].size(), 2u);
  EXPECT_EQ(j["curves"][0]["name"], "cap");
  const double v_mm = j["curves"][0]["volume_ml"].get<double>();
  EXPECT_NEAR(v_mm, cap_volume_ml(), 0.02 * cap_volume_ml());
  EXPECT_NEAR(j["curves"][1]["volume_ml"].get<double>(), 0.0, 1e-3);
  EXPECT_EQ(j["mesh_units"], "mm");
  EXPECT_EQ(j["chest_wall"], "membrane");
  // the region: the grid vertices within the base circle
  const TriangleMesh m = cap_mesh();
  size_t expected = 0;
  for (Index v = 0; v < m.num_vertices(); ++v) expected += std::hypot(m.V(v, 0) - 5, m.V(v, 1)) < kC;
  EXPECT_EQ(j["curves"][0]["region"].size(), expected);
  EXPECT_EQ(j["curves"][0]["region_vertices"].get<size_t>(), expected);

  // The same surface and curves in metres: same volume; only one named curve.
  TriangleMesh in_m = cap_mesh();
  in_m.V *= 0.001;
  io::write_mesh(dir / "cap_m.ply", in_m);
  io::write_markups(dir / "curves_m.mrk.json", cap_markups(), {.units = "m"});
  const std::string in_metres = "volume " + (dir / "cap_m.ply").string() + " -c " + (dir / "curves_m.mrk.json").string();
  const nlohmann::json jm = run_cli_json(in_metres + " --name cap --json");
  ASSERT_EQ(jm["curves"].size(), 1u);
  EXPECT_EQ(jm["mesh_units"], "m");
  EXPECT_NEAR(jm["curves"][0]["volume_ml"].get<double>(), v_mm, 1e-3 * v_mm);
  // thin plate on the mesh as given: it continues the skin's slope around the circle (rising
  // inwards), so it cuts off part of the bump
  const nlohmann::json jt = run_cli_json(in_metres + " --name cap --fill thin-plate --target-edge 0 --json");
  EXPECT_EQ(jt["chest_wall"], "thin_plate");
  EXPECT_EQ(jt["curves"][0]["refinement_levels"], 0);
  EXPECT_GT(jt["curves"][0]["volume_ml"].get<double>(), 0.3 * v_mm);
  EXPECT_LT(jt["curves"][0]["volume_ml"].get<double>(), v_mm);
  fs::remove_all(dir);
}

TEST(VolumeCommand, BadInputIsOneLineWithItsExitCode) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  io::write_mesh(dir / "cap.ply", cap_mesh());
  io::write_markups(dir / "curves.mrk.json", cap_markups());
  const std::string mesh = (dir / "cap.ply").string(), curves = (dir / "curves.mrk.json").string();
  auto one_error_line = [](const std::string& out) {
    return out.find("breastfit: error:") != std::string::npos && out.find('\n') == out.size() - 1;
  };
  std::string out;
  // files: exit 4
  EXPECT_EQ(test::run_cli("volume " + (dir / "nope.ply").string() + " --curves " + curves, &out), 4) << out;
  EXPECT_NE(out.find("nope.ply"), std::string::npos) << out;
  EXPECT_EQ(test::run_cli("volume " + mesh + " --curves " + (dir / "nope.mrk.json").string(), &out), 4) << out;
  // data: exit 3, naming the file and the problem
  EXPECT_EQ(test::run_cli("volume " + mesh + " --curves " + curves + " --name breast_contour_R", &out), 3) << out;
  EXPECT_TRUE(one_error_line(out)) << out;
  EXPECT_NE(out.find("no curve named 'breast_contour_R'"), std::string::npos) << out;
  EXPECT_NE(out.find("curves.mrk.json"), std::string::npos) << out;
  EXPECT_EQ(test::run_cli("volume " + mesh + " --curves " + curves + " --name line", &out), 3) << out;
  EXPECT_NE(out.find("open"), std::string::npos) << out;
  // curves in another frame: far from the surface
  Markups far = cap_markups();
  for (Curve& c : far.curves) c.points.col(2).array() += 500;
  io::write_markups(dir / "far.mrk.json", far);
  EXPECT_EQ(test::run_cli("volume " + mesh + " --curves " + (dir / "far.mrk.json").string(), &out), 3) << out;
  EXPECT_TRUE(one_error_line(out)) << out;
  EXPECT_NE(out.find("curve 'cap'"), std::string::npos) << out;
  EXPECT_NE(out.find("from the surface"), std::string::npos) << out;
  // only points, no closed curve
  Markups only_points;
  only_points.points.push_back({"a", Vec3(1, 2, 3)});
  io::write_markups(dir / "points.mrk.json", only_points);
  EXPECT_EQ(test::run_cli("volume " + mesh + " --curves " + (dir / "points.mrk.json").string(), &out), 3) << out;
  EXPECT_NE(out.find("no closed curve"), std::string::npos) << out;
  // a point cloud
  TriangleMesh cloud = cap_mesh();
  cloud.F.resize(0, 3);
  io::write_mesh(dir / "cloud.ply", cloud);
  EXPECT_EQ(test::run_cli("volume " + (dir / "cloud.ply").string() + " --curves " + curves, &out), 3) << out;
  EXPECT_NE(out.find("point cloud"), std::string::npos) << out;
  // --json prints (as everywhere) and writes nothing: a path after it is not an option value
  const auto size_before = fs::file_size(dir / "curves.mrk.json");
  EXPECT_EQ(test::run_cli("volume " + mesh + " --curves " + curves + " --json " + curves, &out), 2) << out;
  EXPECT_EQ(fs::file_size(dir / "curves.mrk.json"), size_before);
  // command line: exit 2
  EXPECT_EQ(test::run_cli("volume " + mesh + " --curves " + curves + " --fill sphere", &out), 2) << out;
  EXPECT_EQ(test::run_cli("volume " + mesh, &out), 2) << out;
  fs::remove_all(dir);
}

// A synthetic standing scan (no random holes, no misalignment) with its true right breast
// contour, then the same scan with a hole punched inside that contour (around the nipple).
TEST(VolumeCommand, AHoleInsideAContourOfASyntheticScanIsRefused) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  synth::SynthOptions o;
  o.seed = 6;
  o.artifacts.n_holes = 0;
  o.artifacts.n_fragments = 0;
  o.misalign_rotation_deg = 0;
  o.misalign_translation_m = 0;
  const synth::SynthCase c = synth::make_case(*test::default_template(), o);
  Markups curves;
  for (const Curve& k : c.truth_curves)
    if (k.name == "breast_contour_R") curves.curves.push_back(k);
  ASSERT_EQ(curves.curves.size(), 1u);
  io::write_markups(dir / "contour.mrk.json", curves);
  Vec3 nipple = Vec3::Zero();
  for (const auto& p : c.truth_landmarks)
    if (p.name == "nipple_R") nipple = p.position;

  io::write_mesh(dir / "scan.ply", c.scan);
  std::string out;
  const std::string args = " --curves " + (dir / "contour.mrk.json").string();
  ASSERT_EQ(test::run_cli("volume " + (dir / "scan.ply").string() + args, &out), 0) << out;

  TriangleMesh holed = c.scan;
  std::vector<Index> keep;
  for (Index f = 0; f < holed.num_faces(); ++f)
    if ((c.scan.V.row(c.scan.F(f, 0)).transpose() - nipple).norm() > 15.0) keep.push_back(f);
  ASSERT_LT(static_cast<Index>(keep.size()), holed.num_faces());
  holed.F.resize(static_cast<Index>(keep.size()), 3);
  for (size_t i = 0; i < keep.size(); ++i) holed.F.row(static_cast<Index>(i)) = c.scan.F.row(keep[i]);
  io::write_mesh(dir / "holed.ply", holed);
  EXPECT_EQ(test::run_cli("volume " + (dir / "holed.ply").string() + args, &out), 3) << out;
  EXPECT_NE(out.find("curve 'breast_contour_R'"), std::string::npos) << out;
  EXPECT_NE(out.find("1 hole or open border"), std::string::npos) << out;
  EXPECT_NE(out.find("fitted.ply"), std::string::npos) << out;
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
}

}  // namespace
}  // namespace breastfit
