#include "breastfit/synth/case_writer.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/io/markups.h"
#include "support/test_paths.h"
#include "support/toy_model.h"

namespace breastfit::synth {
namespace {

namespace fs = std::filesystem;

SynthCase toy_case(std::uint64_t seed, const std::string& units) {
  SynthOptions o;
  o.seed = seed;
  o.units = units;
  o.artifacts.hole_landmark_clearance_mm = 15.0;
  o.artifacts.hole_radius_mm = {6.0, 10.0};
  static const model::RiggedModel toy = test::make_toy_model();
  return make_case(toy, o);
}

const char* kFiles[] = {"scan.ply", "landmarks.mrk.json", "truth/surface.ply", "truth/landmarks.json",
                        "truth/curves.json", "truth/landmarks.mrk.json", "truth/meta.json"};

TEST(CaseWriter, WritesTheBenchLayout) {
  const fs::path dir = test::temp_dir() / "case";
  const SynthCase c = toy_case(3, "mm");
  write_case(dir, c, false);
  for (const char* f : kFiles) EXPECT_TRUE(fs::is_regular_file(dir / f)) << f;

  const std::string ply = test::file_bytes(dir / "scan.ply");
  EXPECT_NE(ply.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_NE(ply.find("property float x"), std::string::npos);
  EXPECT_NE(ply.find("property list uchar int vertex_indices"), std::string::npos);
  const TriangleMesh scan = io::read_mesh(dir / "scan.ply");
  EXPECT_EQ(scan.num_faces(), c.scan.num_faces());
  EXPECT_LT((scan.V - c.scan.V).cwiseAbs().maxCoeff(), 1e-3);  // float32

  const Markups input = io::read_markups(dir / "landmarks.mrk.json");
  ASSERT_EQ(input.points.size(), c.input_landmarks.size());
  for (const auto& p : c.input_landmarks)
    EXPECT_LT((input.find_point(p.name)->position - p.position).norm(), 1e-5) << p.name;

  const auto lm = nlohmann::json::parse(test::file_bytes(dir / "truth/landmarks.json"));
  for (const auto& p : c.truth_landmarks)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(lm[p.name][k].get<double>(), p.position[k], 1e-6);
  const auto curves = nlohmann::json::parse(test::file_bytes(dir / "truth/curves.json"));
  ASSERT_EQ(curves.size(), c.truth_curves.size());
  for (const auto& cv : c.truth_curves) {
    EXPECT_EQ(curves[cv.name]["closed"].get<bool>(), cv.closed);
    EXPECT_EQ(curves[cv.name]["points"].size(), static_cast<size_t>(cv.points.rows()));
  }
  const auto meta = nlohmann::json::parse(test::file_bytes(dir / "truth/meta.json"));
  EXPECT_EQ(meta["units"], "mm");
  EXPECT_EQ(meta["T_body_to_scan_mm"].size(), 4u);
  EXPECT_TRUE(meta.contains("true_params"));
  EXPECT_TRUE(meta.contains("scan_stats"));
  EXPECT_EQ(meta["seed"].get<int>(), 3);
}

TEST(CaseWriter, MetreCasesDeclareMetres) {
  const fs::path dir = test::temp_dir() / "case_m";
  const SynthCase c = toy_case(4, "m");
  write_case(dir, c, false);
  const std::string mrk = test::file_bytes(dir / "landmarks.mrk.json");
  EXPECT_NE(mrk.find("UCUM"), std::string::npos);
  io::MarkupsReadOptions keep;
  keep.convert_to_mm = false;
  const io::MarkupsFile f = io::read_markups_file(dir / "landmarks.mrk.json", keep);
  EXPECT_EQ(f.units, "m");
  EXPECT_LT((f.markups.points[0].position - c.input_landmarks[0].position).norm(), 1e-9);
  const TriangleMesh scan = io::read_mesh(dir / "scan.ply");
  EXPECT_LT(scan.V.cwiseAbs().maxCoeff(), 5.0);  // metres
}

TEST(CaseWriter, IsByteIdenticalForTheSameSeedAndNeverOverwritesWithoutForce) {
  const fs::path a = test::temp_dir() / "a", b = test::temp_dir() / "b";
  write_case(a, toy_case(5, "mm"), false);
  write_case(b, toy_case(5, "mm"), false);
  for (const char* f : kFiles) EXPECT_EQ(test::file_bytes(a / f), test::file_bytes(b / f)) << f;

  const SynthCase other = toy_case(6, "mm");
  EXPECT_THROW(write_case(a, other, false), IoError);
  EXPECT_EQ(test::file_bytes(a / "truth/meta.json"), test::file_bytes(b / "truth/meta.json"));  // untouched
  std::ofstream(a / "notes.txt") << "mine";
  EXPECT_NO_THROW(write_case(a, other, true));
  EXPECT_NE(test::file_bytes(a / "truth/meta.json"), test::file_bytes(b / "truth/meta.json"));
  EXPECT_EQ(test::file_bytes(a / "notes.txt"), "mine");  // not a file of the case: untouched
  for (const auto& e : fs::directory_iterator(a.parent_path()))  // the staging directory is gone
    EXPECT_EQ(e.path().filename().string().find(".breastfit-tmp-"), std::string::npos) << e.path();
}

TEST(CaseWriter, NamesEveryFileItWrites) {
  const fs::path dir = test::temp_dir() / "case";
  write_case(dir, toy_case(5, "mm"), false);
  size_t n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) n += e.is_regular_file();
  EXPECT_EQ(n, case_file_names().size());
  for (const auto& name : case_file_names()) EXPECT_TRUE(fs::is_regular_file(dir / name)) << name;
}

}  // namespace
}  // namespace breastfit::synth
