// `breastfit register` end to end on synthetic cases made by `breastfit synth` with the shipped
// default template: outputs and units, refusal to overwrite, bad inputs, point clouds, swapped
// labels, landmark-free fits.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <system_error>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "breastfit/io/file_sha256.h"
#include "breastfit/io/io.h"
#include "breastfit/mesh/subdivision.h"
#include "breastfit/mesh/units.h"
#include "breastfit/model/gltf_io.h"
#include "support/read_json.h"
#include "support/test_paths.h"
#include "support/test_shapes.h"
#include "support/toy_model.h"

namespace breastfit {
namespace {

namespace fs = std::filesystem;

using test::read_json;

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

fs::path cases_root() {
  return fs::temp_directory_path() / ("breastfit_register_cases_" + std::to_string(::getpid()));
}

// Removes the synthetic cases when the test program ends.
class CasesCleanup : public ::testing::Environment {
 public:
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(cases_root(), ec);
  }
};
const auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new CasesCleanup);

// One synthetic case per (seed, units), made once per test program run.
fs::path synth_case(int seed, const std::string& units) {
  static const fs::path root = [] {
    const fs::path r = cases_root();
    fs::create_directories(r);
    return r;
  }();
  const fs::path dir = root / ("case_" + std::to_string(seed) + "_" + units);
  if (!fs::exists(dir / "scan.ply")) {
    std::string out;
    const int rc = test::run_cli("synth --quiet --seed " + std::to_string(seed) + " --units " + units + " --out '" +
                                     dir.string() + "'",
                                 &out);
    EXPECT_EQ(rc, 0) << out;
  }
  return dir;
}

TEST(RegisterCommand, WritesEveryOutputInTheScanUnits) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  for (const std::string units : {"mm", "m"}) {
    const fs::path c = synth_case(5, units);
    const fs::path out = test::temp_dir() / units;
    std::string log;
    ASSERT_EQ(test::run_cli("register '" + (c / "scan.ply").string() + "' --landmarks '" +
                                (c / "landmarks.mrk.json").string() + "' --quiet --out '" + out.string() + "'",
                            &log),
              0)
        << log;
    for (const char* f : {"fitted.ply", "landmarks.mrk.json", "drawings.mrk.json", "drawings.ply", "drawings.obj",
                          "scan_painted.ply", "params.json", "report.json", "report.html"})
      EXPECT_TRUE(fs::exists(out / f)) << f;
    const auto report = read_json(out / "report.json");
    EXPECT_GT(report["time_s"].get<double>(), 0.0);
    EXPECT_EQ(report["units"], units == "mm" ? "mm" : "m");
    EXPECT_LT(report["table1"]["surface_mm"]["mae"].get<double>(), 3.0);
    EXPECT_LT(report["table1"]["landmarks_mm"]["mae"].get<double>(), 8.0);
    const TriangleMesh fitted = io::read_mesh(out / "fitted.ply");
    const double extent = mesh::max_extent(fitted.V);
    if (units == "m") EXPECT_LT(extent, 2.0);
    else EXPECT_GT(extent, 200.0);
  }
}

TEST(RegisterCommand, ReportsAreTraceable) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path c = synth_case(5, "mm");
  const fs::path out = test::temp_dir() / "out";
  std::string log;
  ASSERT_EQ(test::run_cli("register '" + (c / "scan.ply").string() + "' -l '" + (c / "landmarks.mrk.json").string() +
                              "' --lambda-landmarks 0.5 --quiet --no-report-html -o '" + out.string() + "'",
                          &log),
            0)
      << log;
  const auto report = read_json(out / "report.json");
  const auto& p = report["provenance"];
  EXPECT_FALSE(p["breastfit_version"].get<std::string>().empty());
  EXPECT_EQ(p["inputs"]["scan"]["path"], (c / "scan.ply").string());
  EXPECT_EQ(p["inputs"]["scan"]["sha256"], io::file_sha256_hex(c / "scan.ply"));
  EXPECT_EQ(p["inputs"]["landmarks"]["sha256"], io::file_sha256_hex(c / "landmarks.mrk.json"));
  EXPECT_EQ(p["inputs"]["template"]["sha256"].get<std::string>().size(), 64u);
  EXPECT_FALSE(p["inputs"].contains("config"));
  EXPECT_EQ(p["fit_options"]["weights"]["lambda_landmarks"], 0.5) << p["fit_options"].dump();
  EXPECT_TRUE(std::regex_match(report["run"]["started_utc"].get<std::string>(),
                               std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")));
  EXPECT_NE(report["run"]["command_line"].get<std::string>().find("--lambda-landmarks 0.5"), std::string::npos);
  const auto params = read_json(out / "params.json");
  EXPECT_EQ(params["template"]["sha256"], p["inputs"]["template"]["sha256"]);
  EXPECT_FALSE(params["template"]["name"].get<std::string>().empty());
  // The fitted landmarks are not mistaken for the input ones in 3D Slicer.
  const auto fitted_landmarks = read_json(out / "landmarks.mrk.json");
  EXPECT_EQ(fitted_landmarks["markups"][0]["name"], "breastfit fitted landmarks");
  EXPECT_TRUE(fitted_landmarks["markups"][0]["display"].contains("selectedColor"));
}

// With report.html a fit from landmarks draws the scan's layers on a thread of its own: the automatic
// thread count leaves that thread a core (the fit's count is recorded, at least 1, no longer 0 =
// automatic); an explicit --threads is kept, and without report.html the count stays automatic.
TEST(RegisterCommand, LeavesTheReportLayersACoreWhenTheThreadsAreAutomatic) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  if (std::getenv("OMP_NUM_THREADS")) GTEST_SKIP() << "OMP_NUM_THREADS fixes the count";
  const fs::path c = synth_case(5, "mm");
  const auto threads = [&](const std::string& extra, const std::string& name) {
    const fs::path out = test::temp_dir() / name;
    std::string log;
    EXPECT_EQ(test::run_cli("register '" + (c / "scan.ply").string() + "' -l '" + (c / "landmarks.mrk.json").string() +
                                "' --quiet " + extra + " -o '" + out.string() + "'",
                            &log),
              0)
        << log;
    return read_json(out / "report.json")["provenance"]["fit_options"]["threads"].get<int>();
  };
  EXPECT_GE(threads("", "auto"), 1);
  EXPECT_EQ(threads("--threads 2", "two"), 2);
  EXPECT_EQ(threads("--no-report-html", "plain"), 0);
}

TEST(RegisterCommand, RefusesATemplateThatIsNotATorso) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  model::RiggedModel rig = test::make_toy_model();  // a rig without landmarks or drawings
  rig.landmarks.clear();
  rig.drawings.clear();
  const fs::path dir = test::temp_dir();
  model::save_gltf(dir / "rig.glb", rig);
  const fs::path c = synth_case(5, "mm");
  std::string log;
  EXPECT_EQ(test::run_cli("register '" + (c / "scan.ply").string() + "' --no-landmarks -t '" + (dir / "rig.glb").string() +
                              "' --quiet -o '" + (dir / "out").string() + "'",
                          &log),
            3);
  EXPECT_NE(log.find("has no landmarks and no drawings: not a breastfit torso template"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir / "out" / "report.json"));
}

TEST(RegisterCommand, NeverOverwritesWithoutForce) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path c = synth_case(5, "mm");
  const fs::path out = test::temp_dir();
  std::ofstream(out / "report.json") << "mine";
  std::string log;
  const int rc = test::run_cli("register '" + (c / "scan.ply").string() + "' --landmarks '" +
                                   (c / "landmarks.mrk.json").string() + "' --quiet --out '" + out.string() + "'",
                               &log);
  EXPECT_EQ(rc, 4) << log;
  EXPECT_NE(log.find("--force"), std::string::npos) << log;
  std::ifstream f(out / "report.json");
  std::string content;
  f >> content;
  EXPECT_EQ(content, "mine");
}

TEST(RegisterCommand, BadInputsGiveOneLineAndANonZeroExit) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path c = synth_case(5, "mm");
  const fs::path dir = test::temp_dir();
  std::string log;
  // missing scan
  EXPECT_EQ(test::run_cli("register '" + (dir / "nope.ply").string() + "' --out '" + (dir / "o1").string() + "'", &log), 4);
  EXPECT_NE(log.find("nope.ply"), std::string::npos) << log;
  // unknown landmark name
  std::ofstream(dir / "bad.csv") << "belly_button,1,2,3\n";
  EXPECT_EQ(test::run_cli("register '" + (c / "scan.ply").string() + "' --landmarks '" + (dir / "bad.csv").string() +
                              "' --out '" + (dir / "o2").string() + "'",
                          &log),
            4);
  EXPECT_NE(log.find("belly_button"), std::string::npos) << log;
  // a scan that is far too small for a torso
  TriangleMesh scan = io::read_mesh(c / "scan.ply");
  scan.V *= 0.05;
  io::write_mesh(dir / "tiny.ply", scan);
  EXPECT_EQ(test::run_cli("register '" + (dir / "tiny.ply").string() + "' --units mm --out '" + (dir / "o3").string() + "'",
                          &log),
            3);
  EXPECT_NE(log.find("not an upper torso"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir / "o3" / "fitted.ply"));
}

TEST(RegisterCommand, CorrectsSwappedLeftRightLabelsWithAWarning) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path c = synth_case(5, "mm");
  const fs::path dir = test::temp_dir();
  std::ifstream in(c / "landmarks.mrk.json");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  // exchange every _R and _L label
  for (auto [from, to] : {std::pair<std::string, std::string>{"_R\"", "_X\""}, {"_L\"", "_R\""}, {"_X\"", "_L\""}}) {
    for (size_t p = text.find(from); p != std::string::npos; p = text.find(from, p + to.size())) text.replace(p, from.size(), to);
  }
  std::ofstream(dir / "swapped.mrk.json") << text;
  std::string log;
  ASSERT_EQ(test::run_cli("register '" + (c / "scan.ply").string() + "' --landmarks '" +
                              (dir / "swapped.mrk.json").string() + "' --quiet --out '" + (dir / "out").string() + "'",
                          &log),
            0)
      << log;
  EXPECT_NE(log.find("swapped"), std::string::npos) << log;
  EXPECT_LT(read_json(dir / "out" / "report.json")["table1"]["landmarks_mm"]["mae"].get<double>(), 8.0);
}

TEST(RegisterCommand, RegistersAPointCloud) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path c = synth_case(5, "mm");
  const fs::path dir = test::temp_dir();
  TriangleMesh cloud = io::read_mesh(c / "scan.ply");
  cloud.F.resize(0, 3);
  io::write_mesh(dir / "cloud.ply", cloud);
  std::string log;
  ASSERT_EQ(test::run_cli("register '" + (dir / "cloud.ply").string() + "' --landmarks '" +
                              (c / "landmarks.mrk.json").string() + "' --quiet --out '" + (dir / "out").string() + "'",
                          &log),
            0)
      << log;
  const auto report = read_json(dir / "out" / "report.json");
  EXPECT_TRUE(report["point_cloud"].get<bool>());
  EXPECT_LT(report["table1"]["surface_mm"]["mae"].get<double>(), 3.0);
}

TEST(RegisterCommand, WithoutLandmarksSaysWhichInitialisationItUsed) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path c = synth_case(5, "mm");
  const fs::path out = test::temp_dir() / "out";
  std::string log;
  const int rc = test::run_cli("register '" + (c / "scan.ply").string() + "' --quiet --out '" + out.string() + "'", &log);
  ASSERT_TRUE(rc == 0 || rc == 5) << log;  // converged, or said clearly that it did not
  const auto report = read_json(out / "report.json");
  EXPECT_EQ(report["solver"]["initialization"], "landmark-free");
  EXPECT_EQ(report["status"], rc == 0 ? "ok" : "not_usable");
}

TEST(RegisterCommand, IsDeterministic) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path c = synth_case(5, "mm");
  const fs::path dir = test::temp_dir();
  std::string log;
  for (const char* name : {"a", "b"})
    ASSERT_EQ(test::run_cli("register '" + (c / "scan.ply").string() + "' --landmarks '" +
                                (c / "landmarks.mrk.json").string() + "' --quiet --out '" + (dir / name).string() + "'",
                            &log),
              0);
  for (const char* f : {"fitted.ply", "landmarks.mrk.json", "drawings.mrk.json", "params.json"})
    EXPECT_EQ(read_text(dir / "a" / f), read_text(dir / "b" / f)) << f;
  // report.json: the provenance block is deterministic; only the run block (time, command line)
  // and the measured times differ.
  const auto report_a = read_json(dir / "a" / "report.json"), report_b = read_json(dir / "b" / "report.json");
  ASSERT_TRUE(report_a.contains("provenance"));
  EXPECT_EQ(report_a["provenance"], report_b["provenance"]);
  EXPECT_NE(report_a["run"]["command_line"], report_b["run"]["command_line"]);  // --out differs
  // report.html: identical but for the measured registration time and the run rows (start
  // time, command line).
  const std::regex time_s("Registration time</th><td>[0-9.]+ s");
  const std::regex run_rows("<tbody class=\"run\">[\\s\\S]*?</tbody>");
  const std::string html_a = read_text(dir / "a" / "report.html"), html_b = read_text(dir / "b" / "report.html");
  ASSERT_TRUE(std::regex_search(html_a, time_s));
  ASSERT_TRUE(std::regex_search(html_a, run_rows));
  auto strip = [&](const std::string& h) { return std::regex_replace(std::regex_replace(h, time_s, "T"), run_rows, "R"); };
  EXPECT_EQ(strip(html_a), strip(html_b));
}

TEST(RegisterCommand, WritesAReportHtmlUnlessAskedNotTo) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path c = synth_case(5, "mm");
  const fs::path out = test::temp_dir() / "out";
  const std::string cmd = "register '" + (c / "scan.ply").string() + "' --landmarks '" +
                          (c / "landmarks.mrk.json").string() + "' --out '" + out.string() + "'";
  std::string log;
  ASSERT_EQ(test::run_cli(cmd, &log), 0) << log;
  EXPECT_NE(log.find("report.html"), std::string::npos) << log;
  const std::string html = read_text(out / "report.html");
  EXPECT_NE(html.find((c / "scan.ply").string()), std::string::npos);
  EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  for (const char* curve : {"breast_contour_R", "breast_contour_L", "sternum"})
    EXPECT_NE(html.find(curve), std::string::npos) << curve;
  // --no-report-html with --force: no report, and the previous one is gone.
  ASSERT_EQ(test::run_cli(cmd + " --force --no-report-html", &log), 0) << log;
  EXPECT_FALSE(fs::exists(out / "report.html"));
  EXPECT_TRUE(fs::exists(out / "report.json"));
  EXPECT_EQ(log.find("report.html"), std::string::npos) << log;
}


TEST(RegisterCommand, AFailingRunLeavesOnlyItsReportNeverTheStaleFit) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path c = synth_case(5, "mm");
  const fs::path dir = test::temp_dir();
  const fs::path out = dir / "out";
  const std::string cmd = "register '" + (c / "scan.ply").string() + "' --landmarks '" +
                          (c / "landmarks.mrk.json").string() + "' --quiet --out '" + out.string() + "'";
  std::string log;
  ASSERT_EQ(test::run_cli(cmd, &log), 0) << log;
  ASSERT_TRUE(fs::exists(out / "fitted.ply"));
  ASSERT_TRUE(fs::exists(out / "report.html"));
  std::ofstream(out / "notes.txt") << "the surgeon's own file\n";
  // A leftover staging directory of a killed run into the same --out.
  const fs::path leftover = dir / ".out.breastfit-tmp-1-0";
  fs::create_directories(leftover);
  std::ofstream(leftover / "fitted.ply") << "partial";
  // The same scan with a surface tolerance no fit can meet: not usable (exit 5).
  std::ofstream(dir / "strict.json") << R"({"max_surface_mae_mm": 0.001})";
  ASSERT_EQ(test::run_cli(cmd + " --force --config '" + (dir / "strict.json").string() + "'", &log), 5) << log;
  for (const char* name : {"fitted.ply", "landmarks.mrk.json", "drawings.mrk.json", "drawings.ply", "drawings.obj",
                           "scan_painted.ply", "params.json", "report.html"})
    EXPECT_FALSE(fs::exists(out / name)) << name << " of the previous run is still there";
  EXPECT_EQ(read_json(out / "report.json")["status"], "not_usable");
  EXPECT_EQ(read_text(out / "notes.txt"), "the surgeon's own file\n");  // not ours: untouched
  EXPECT_FALSE(fs::exists(leftover));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".breastfit-tmp-"), std::string::npos) << e.path();
  // `breastfit map` refuses the failed fit with a clear message.
  EXPECT_NE(test::run_cli("map '" + (c / "landmarks.mrk.json").string() + "' --from '" + out.string() + "' --to '" +
                              out.string() + "' --out '" + (dir / "m.mrk.json").string() + "'",
                          &log),
            0);
  EXPECT_NE(log.find("not usable"), std::string::npos) << log;
}

// Shapes that are not a torso, made here: registered without landmarks they must not be "ok".
// Either the fit is not usable (exit 5), or it is judged implausible (exit 7, every output
// written, report.json "status": "implausible" with the problems), or the scan is refused (exit 3).
TEST(RegisterCommand, ShapesThatAreNotATorsoAreNotReportedOk) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  io::write_mesh(dir / "sphere.ply", test::sphere_mesh(160.0, Vec3::Zero(), 48, 96));
  TriangleMesh box = test::cube_mesh(1.0);
  box.V.col(0) *= 170.0;  // 340 x 500 x 220 mm
  box.V.col(1) *= 250.0;
  box.V.col(2) *= 110.0;
  for (int k = 0; k < 4; ++k) box = mesh::subdivide(box, /*loop=*/false);  // ~10 mm triangles
  io::write_mesh(dir / "box.ply", box);
  // A torso at x0.4 and x0.15 of its size (in mm).
  TriangleMesh torso = io::read_mesh(synth_case(5, "mm") / "scan.ply");
  const Eigen::RowVector3d centre = torso.V.colwise().mean();
  for (double k : {0.4, 0.15}) {
    TriangleMesh small = torso;
    small.V = ((torso.V.rowwise() - centre) * k).rowwise() + centre;
    io::write_mesh(dir / ("torso_x" + std::to_string(static_cast<int>(k * 100)) + ".ply"), small);
  }
  for (const char* name : {"sphere", "box", "torso_x40", "torso_x15"}) {
    const fs::path out = dir / (std::string(name) + "_out");
    std::string log;
    const int rc = test::run_cli("register '" + (dir / (std::string(name) + ".ply")).string() +
                                     "' --units mm --quiet --no-report-html --out '" + out.string() + "'",
                                 &log);
    EXPECT_TRUE(rc == 3 || rc == 5 || rc == 7) << name << " exit " << rc << "\n" << log;
    if (rc == 3) continue;  // refused before the fit, with its reason
    const auto report = read_json(out / "report.json");
    EXPECT_NE(report["status"], "ok") << name;
    if (rc == 7) {
      EXPECT_EQ(report["status"], "implausible") << name;
      EXPECT_FALSE(report["plausibility"]["problems"].empty()) << name;
      EXPECT_TRUE(fs::exists(out / "fitted.ply")) << name;
      EXPECT_NE(log.find("implausible fit:"), std::string::npos) << log;
    }
    std::printf("%s: exit %d, status %s, problems %s, coverage %.2f\n", name, rc,
                report["status"].get<std::string>().c_str(), report["plausibility"]["problems"].dump().c_str(),
                report["scan_coverage"]["fraction"].get<double>());
  }
}

TEST(RegisterCommand, ASyntheticTorsoIsPlausible) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  for (const int seed : {5, 6}) {
    const fs::path c = synth_case(seed, "mm");
    const fs::path out = test::temp_dir() / ("s" + std::to_string(seed));
    std::string log;
    ASSERT_EQ(test::run_cli("register '" + (c / "scan.ply").string() + "' --landmarks '" +
                                (c / "landmarks.mrk.json").string() + "' --quiet --no-report-html --out '" +
                                out.string() + "'",
                            &log),
              0)
        << log;
    const auto report = read_json(out / "report.json");
    EXPECT_EQ(report["status"], "ok");
    EXPECT_TRUE(report["plausibility"]["plausible"].get<bool>()) << report["plausibility"].dump();
    EXPECT_GT(report["scan_coverage"]["fraction"].get<double>(), 0.3);
    EXPECT_EQ(report["table1"]["surface_mm"]["n"].get<int>(), report["scan_coverage"]["covered_vertices"].get<int>());
  }
}

}  // namespace
}  // namespace breastfit
