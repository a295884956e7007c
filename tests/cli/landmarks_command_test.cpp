// `breastfit landmarks` and `register` without (or with few) landmarks, end to end on synthetic
// cases turned every way (up to 180°, far away) and written in millimetres or metres.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "breastfit/core/types.h"
#include "support/read_json.h"
#include "support/test_paths.h"

namespace breastfit {
namespace {

namespace fs = std::filesystem;

using test::read_json;

// A synthetic case in `root`, rotated up to `rotation_deg` about a random axis, up to 1 m away.
fs::path turned_case(const fs::path& root, int seed, const std::string& pose, const std::string& units,
                     int rotation_deg) {
  const fs::path dir = root / ("case_" + std::to_string(seed) + pose + units);
  std::string log;
  EXPECT_EQ(test::run_cli("synth --quiet --seed " + std::to_string(seed) + " --pose " + pose + " --units " + units +
                              " --rotation-deg " + std::to_string(rotation_deg) + " --translation-m 1 --out '" +
                              dir.string() + "'",
                          &log),
            0)
      << log;
  return dir;
}

// Control points of a markups file by label (file units).
std::map<std::string, Vec3> markup_points(const fs::path& p) {
  std::map<std::string, Vec3> out;
  const auto markups = read_json(p);  // kept alive over the loop
  for (const auto& cp : markups["markups"][0]["controlPoints"])
    out[cp["label"].get<std::string>()] =
        Vec3(cp["position"][0].get<double>(), cp["position"][1].get<double>(), cp["position"][2].get<double>());
  return out;
}

// Mean distance (mm) of the landmarks in `found` (a markups file) from the case's truth.
double mean_error_mm(const fs::path& found, const fs::path& case_dir, double to_mm) {
  const auto truth = read_json(case_dir / "truth" / "landmarks.json");
  const auto points = markup_points(found);
  double sum = 0;
  int n = 0;
  for (const auto& [name, p] : points) {
    if (!truth.contains(name)) continue;
    const Vec3 t(truth[name][0].get<double>(), truth[name][1].get<double>(), truth[name][2].get<double>());
    sum += to_mm * (p - t).norm();
    ++n;
  }
  EXPECT_GT(n, 0);
  return n ? sum / n : 1e9;
}

TEST(LandmarksCommand, FindsTheLandmarksOfATurnedScanInMetresAndRegisterAcceptsThem) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  const fs::path c = turned_case(dir, 21, "standing", "m", 180);
  std::string log;
  ASSERT_EQ(test::run_cli("landmarks '" + (c / "scan.ply").string() + "' --json --out '" + (dir / "L.mrk.json").string() +
                              "'",
                          &log),
            0)
      << log;
  const auto j = nlohmann::json::parse(log.substr(log.find('{')));
  EXPECT_EQ(j["units"], "m");
  ASSERT_EQ(j["landmarks"].size(), 12u);
  for (const auto& l : j["landmarks"]) {
    EXPECT_GE(l["confidence"].get<double>(), 0.0);
    EXPECT_LE(l["confidence"].get<double>(), 1.0);
  }
  EXPECT_EQ(markup_points(dir / "L.mrk.json").size(), 12u);
  EXPECT_LT(mean_error_mm(dir / "L.mrk.json", c, 1000.0), 30.0);
  ASSERT_EQ(test::run_cli("register '" + (c / "scan.ply").string() + "' --landmarks '" + (dir / "L.mrk.json").string() +
                              "' --quiet --no-report-html --out '" + (dir / "out").string() + "'",
                          &log),
            0)
      << log;
}

TEST(LandmarksCommand, RefusesToOverwriteWithoutForce) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  std::ofstream(dir / "L.mrk.json") << "{}";
  std::string log;
  EXPECT_NE(test::run_cli("landmarks '" + (dir / "missing.ply").string() + "' --out '" + (dir / "L.mrk.json").string() + "'",
                          &log),
            0);
}

TEST(RegisterWithoutLandmarks, SaysSoInOneLineAndNeverFlipsATurnedScan) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  struct Case {
    int seed;
    const char* pose;
    const char* units;
  };
  const fs::path dir = test::temp_dir();
  for (const Case k : {Case{31, "standing", "mm"}, Case{32, "supine", "m"}, Case{33, "standing", "m"}}) {
    const fs::path c = turned_case(dir, k.seed, k.pose, k.units, 180);
    const fs::path out = dir / ("out" + std::to_string(k.seed));
    std::string log;
    ASSERT_EQ(test::run_cli("register '" + (c / "scan.ply").string() + "' --quiet --no-report-html --out '" +
                                out.string() + "'",
                            &log),
              0)
        << log;
    EXPECT_NE(log.find("no landmarks given: landmark-free"), std::string::npos) << log;
    const auto report = read_json(out / "report.json");
    EXPECT_EQ(report["solver"]["initialization"], "landmark-free");
    EXPECT_FALSE(report["solver"]["orientation"]["chosen"].get<std::string>().empty());
    const double to_mm = std::string(k.units) == "m" ? 1000.0 : 1.0;
    EXPECT_LT(mean_error_mm(out / "landmarks.mrk.json", c, to_mm), 30.0) << k.seed << " " << k.pose;
  }
}

TEST(RegisterWithFewLandmarks, ThreeLandmarksInitialiseAndFit) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  const fs::path c = turned_case(dir, 41, "supine", "mm", 180);
  auto m = read_json(c / "landmarks.mrk.json");
  auto& cps = m["markups"][0]["controlPoints"];
  nlohmann::json kept = nlohmann::json::array();
  for (const auto& cp : cps)
    if (cp["label"] == "sternal_notch" || cp["label"] == "nipple_R" || cp["label"] == "nipple_L") kept.push_back(cp);
  cps = kept;
  std::ofstream(dir / "three.mrk.json") << m.dump(1);
  std::string log;
  ASSERT_EQ(test::run_cli("register '" + (c / "scan.ply").string() + "' --landmarks '" + (dir / "three.mrk.json").string() +
                              "' --quiet --no-report-html --out '" + (dir / "out").string() + "'",
                          &log),
            0)
      << log;
  const auto report = read_json(dir / "out" / "report.json");
  EXPECT_EQ(report["solver"]["initialization"], "landmarks");
  EXPECT_EQ(report["solver"]["landmarks_used"], 3);
  // 12.3 mm before session 14, 15.9 mm since the sternum's length is predicted from the notch and
  // nipples (fit/sternum_length.h): the proportion overshoots this template-made torso's true sternum
  // by 5.2 mm (1.6 residuals; the 10 mm of session 14 was measured to the annotated xiphoid), the
  // shape stage's length falls 3.0 mm short, and with the xiphoid held the shoulder's and the folds'
  // targets move with it. On the three benchmark-like sets and 13 template-made torsos the proportion
  // beats the fitted length and the blends of the two tried (docs/REGISTRATION.md, Session 15 of 3 landmarks).
  EXPECT_LT(mean_error_mm(dir / "out" / "landmarks.mrk.json", c, 1.0), 17.0);
}

}  // namespace
}  // namespace breastfit
