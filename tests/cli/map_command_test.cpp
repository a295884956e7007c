// `breastfit map` end to end on two fake `register` output directories of the toy template.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "breastfit/io/io.h"
#include "breastfit/io/markups.h"
#include "breastfit/model/gltf_io.h"
#include "breastfit/model/params_json.h"
#include "breastfit/model/pose_evaluator.h"
#include "support/test_paths.h"
#include "support/toy_model.h"

namespace breastfit {
namespace {

namespace fs = std::filesystem;

struct FakeFit {
  fs::path dir;
  TriangleMesh fitted_mm;
};

// What `breastfit register` writes that `map` reads: params.json (mm), fitted.ply and
// report.json in the scan's units.
FakeFit fake_fit(const fs::path& dir, const model::RiggedModel& m, std::uint64_t seed, const std::string& units) {
  fs::create_directories(dir);
  const model::PoseParams p = test::random_toy_pose(m, seed, 0.6);
  model::write_params_json(dir / "params.json", m, p);
  FakeFit f{dir, {}};
  f.fitted_mm.V = model::pose_vertices(m, p);
  f.fitted_mm.F = m.rest.F;
  TriangleMesh file = f.fitted_mm;
  if (units == "m") file.V *= 0.001;
  io::write_mesh(dir / "fitted.ply", file);
  std::ofstream(dir / "report.json") << nlohmann::json{{"units", units}, {"time_s", 0.1}}.dump();
  return f;
}

Markups drawings_on(const model::RiggedModel& m, const TriangleMesh& fit) {
  Markups out;
  for (const auto& d : m.drawings) {
    Curve c{d.name, d.closed, Points(static_cast<Eigen::Index>(d.points.size()), 3)};
    for (size_t i = 0; i < d.points.size(); ++i) c.points.row(static_cast<Eigen::Index>(i)) = d.points[i].position(fit.V, fit.F).transpose();
    out.curves.push_back(c);
  }
  out.points.push_back({"nipple_R", m.landmarks[*m.landmark_index("nipple_R")].point.position(fit.V, fit.F)});
  return out;
}

double max_diff(const Markups& a, const Markups& b) {
  double d = 0;
  if (a.curves.size() != b.curves.size() || a.points.size() != b.points.size()) return 1e30;
  for (size_t i = 0; i < a.points.size(); ++i) d = std::max(d, (a.points[i].position - b.points[i].position).norm());
  for (size_t i = 0; i < a.curves.size(); ++i) {
    if (a.curves[i].points.rows() != b.curves[i].points.rows() || a.curves[i].closed != b.curves[i].closed ||
        a.curves[i].name != b.curves[i].name)
      return 1e30;
    d = std::max(d, (a.curves[i].points - b.curves[i].points).rowwise().norm().maxCoeff());
  }
  return d;
}

TEST(MapCommand, MapsToItselfAndToAnotherFit) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  const model::RiggedModel m = test::make_toy_model();
  const fs::path tpl = dir / "toy.glb";
  model::save_gltf(tpl, m);
  const model::RiggedModel loaded = model::load_gltf(tpl);  // what the CLI poses
  const FakeFit a = fake_fit(dir / "fit_a", loaded, 1, "mm");
  const FakeFit b = fake_fit(dir / "fit_b", loaded, 2, "m");
  const Markups on_a = drawings_on(loaded, a.fitted_mm);
  io::write_markups(dir / "in.mrk.json", on_a);

  std::string out;
  const std::string common = " --template " + tpl.string() + " " + (dir / "in.mrk.json").string();
  ASSERT_EQ(test::run_cli("map --from " + a.dir.string() + " --to " + a.dir.string() + common + " --out " +
                              (dir / "self.mrk.json").string(),
                          &out),
            0)
      << out;
  EXPECT_NE(out.find("high"), std::string::npos) << out;
  EXPECT_LT(max_diff(io::read_markups(dir / "self.mrk.json"), on_a), 1e-9);
  ASSERT_TRUE(fs::exists(dir / "self.confidence.json"));
  std::ifstream cf(dir / "self.confidence.json");
  const nlohmann::json conf = nlohmann::json::parse(cf);
  EXPECT_EQ(conf["summary"]["low"], 0);
  EXPECT_EQ(conf["points"].size(), static_cast<size_t>(conf["summary"]["points"].get<int>()));

  ASSERT_EQ(test::run_cli("map --quiet --from " + a.dir.string() + " --to " + b.dir.string() + common + " --out " +
                              (dir / "ab.mrk.json").string(),
                          &out),
            0)
      << out;
  const io::MarkupsFile ab = io::read_markups_file(dir / "ab.mrk.json", {.convert_to_mm = false});
  EXPECT_EQ(ab.units, "m");  // B's units
  EXPECT_LT(max_diff(io::read_markups(dir / "ab.mrk.json"), drawings_on(loaded, b.fitted_mm)), 1e-6);

  // onto scan B: fitted B pushed 1.5 mm outwards along its normals, in B's units (m)
  {
    TriangleMesh scan = b.fitted_mm;
    Points N = Points::Zero(scan.V.rows(), 3);
    for (Index f = 0; f < scan.num_faces(); ++f) {
      const Vec3 n = (scan.V.row(scan.F(f, 1)) - scan.V.row(scan.F(f, 0)))
                         .cross(scan.V.row(scan.F(f, 2)) - scan.V.row(scan.F(f, 0)))
                         .transpose();
      for (int k = 0; k < 3; ++k) N.row(scan.F(f, k)) += n.transpose();
    }
    for (Index v = 0; v < scan.num_vertices(); ++v) scan.V.row(v) += 1.5 * N.row(v).normalized();
    scan.V *= 0.001;
    io::write_mesh(dir / "scan_b.ply", scan);
    ASSERT_EQ(test::run_cli("map --from " + a.dir.string() + " --to " + b.dir.string() + common + " --out " +
                                (dir / "ab_scan.mrk.json").string() + " --to-scan " + (dir / "scan_b.ply").string(),
                            &out),
              0)
        << out;
    EXPECT_NE(out.find("supported by scan B"), std::string::npos) << out;
    std::ifstream sf(dir / "ab_scan.confidence.json");
    const nlohmann::json sc = nlohmann::json::parse(sf);
    EXPECT_GT(sc["summary"]["supported_by_scan_b"].get<int>(), sc["summary"]["points"].get<int>() / 2);
    for (const auto& p : sc["points"])
      if (p["supported_by_scan_b"].get<bool>()) EXPECT_NEAR(p["scan_b_offset_mm"].get<double>(), 1.5, 0.4);
  }

  // refuses to overwrite; one-line IoError (exit 4) for a fit of another template
  EXPECT_NE(test::run_cli("map --quiet --from " + a.dir.string() + " --to " + b.dir.string() + common + " --out " +
                          (dir / "ab.mrk.json").string()),
            0);
  TriangleMesh wrong = b.fitted_mm;
  wrong.V.array() += 5.0;
  io::write_mesh(b.dir / "fitted.ply", wrong);  // mm numbers in a metre fit: mismatch
  EXPECT_EQ(test::run_cli("map --quiet --from " + a.dir.string() + " --to " + b.dir.string() + common + " --out " +
                              (dir / "bad.mrk.json").string(),
                          &out),
            4)
      << out;
  EXPECT_NE(out.find("breastfit: error:"), std::string::npos) << out;
  EXPECT_EQ(test::run_cli("map --quiet --from " + (dir / "nope").string() + " --to " + b.dir.string() + common +
                          " --out " + (dir / "bad.mrk.json").string()),
            4);
}

TEST(MapCommand, MeshChoosesOneSkinnedMeshOfATemplate) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  const fs::path two = test::save_two_mesh_toy(dir);
  const model::RiggedModel loaded = model::load_gltf(two, "Second");
  const FakeFit a = fake_fit(dir / "fit_a", loaded, 1, "mm");
  io::write_markups(dir / "in.mrk.json", drawings_on(loaded, a.fitted_mm));
  std::string out;
  const std::string common = "map --quiet --from " + a.dir.string() + " --to " + a.dir.string() + " --template " +
                             two.string() + " " + (dir / "in.mrk.json").string() + " --out " + (dir / "o.mrk.json").string();
  EXPECT_EQ(test::run_cli(common, &out), 4) << out;
  EXPECT_NE(out.find("choose one with --mesh NAME"), std::string::npos) << out;
  ASSERT_EQ(test::run_cli(common + " --mesh Second", &out), 0) << out;
  EXPECT_TRUE(fs::exists(dir / "o.mrk.json"));
}

}  // namespace
}  // namespace breastfit
