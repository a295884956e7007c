#include "breastfit/pipeline/landmark_frame_check.h"

#include <gtest/gtest.h>

#include "breastfit/synth/synth_case.h"
#include "support/default_template.h"
#include "support/test_shapes.h"

namespace breastfit::pipeline {
namespace {

// A "body" (sphere of radius 150 mm) away from the scanner's origin, and landmarks on it.
struct BodyScan {
  fit::ScanTarget scan{test::sphere_mesh(150.0, Vec3(400, 250, 120)), 200};
  std::vector<std::pair<std::string, Vec3>> on_scan() const {
    std::vector<std::pair<std::string, Vec3>> out;
    const Vec3 c(400, 250, 120);
    int k = 0;
    for (const Vec3 dir : {Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(-1, 1, 0).normalized(), Vec3(0, 1, 1).normalized()})
      out.emplace_back("p" + std::to_string(k++), c + 150.0 * dir);
    return out;
  }
  template <typename F>
  std::vector<std::pair<std::string, Vec3>> mapped(F f) const {
    auto out = on_scan();
    for (auto& [n, p] : out) p = f(p);
    return out;
  }
};

TEST(LandmarkFrameCheck, LandmarksOnTheScanNeedNoDiagnosis) {
  BodyScan s;
  EXPECT_FALSE(diagnose_landmark_frame(s.on_scan(), s.scan));
}

TEST(LandmarkFrameCheck, NamesRasReadAsLps) {
  BodyScan s;
  const auto d = diagnose_landmark_frame(s.mapped([](const Vec3& p) { return Vec3(-p.x(), -p.y(), p.z()); }), s.scan);
  ASSERT_TRUE(d);
  EXPECT_NE(d->mistake.find("RAS"), std::string::npos) << d->mistake;
  EXPECT_GT(d->median_distance_mm, 300.0);
  EXPECT_LT(d->corrected_median_mm, 1.0);
}

TEST(LandmarkFrameCheck, NamesAFactorOf1000EitherWay) {
  BodyScan s;
  const auto metres = diagnose_landmark_frame(s.mapped([](const Vec3& p) { return Vec3(p / 1000.0); }), s.scan);
  ASSERT_TRUE(metres);
  EXPECT_NE(metres->mistake.find("in metres but read as millimetres"), std::string::npos) << metres->mistake;
  const auto mm = diagnose_landmark_frame(s.mapped([](const Vec3& p) { return Vec3(p * 1000.0); }), s.scan);
  ASSERT_TRUE(mm);
  EXPECT_NE(mm->mistake.find("in millimetres but read as metres"), std::string::npos) << mm->mistake;
}

TEST(LandmarkFrameCheck, LandmarksOfAnotherScanAreNotMisdiagnosed) {
  BodyScan s;
  // Far away, and no usual mistake brings them back: no diagnosis (the fit reports it).
  EXPECT_FALSE(diagnose_landmark_frame(s.mapped([](const Vec3& p) { return Vec3(p + Vec3(900, 0, 0)); }), s.scan));
  // Fewer than 3 landmarks: nothing to say.
  auto two = s.mapped([](const Vec3& p) { return Vec3(-p.x(), -p.y(), p.z()); });
  two.resize(2);
  EXPECT_FALSE(diagnose_landmark_frame(two, s.scan));
}

// A synthetic torso scan and its 12 landmarks: each usual mistake named, the landmarks as given
// left alone.
TEST(LandmarkFrameCheck, NamesEachMistakeOnASyntheticTorso) {
  synth::SynthOptions o;
  o.seed = 22;
  o.pose = synth::PoseType::Supine;
  const synth::SynthCase c = synth::make_case(*test::default_template(), o);
  const fit::ScanTarget scan(c.scan, 300);
  std::vector<std::pair<std::string, Vec3>> given;
  for (const auto& p : c.input_landmarks) given.emplace_back(p.name, p.position);
  EXPECT_FALSE(diagnose_landmark_frame(given, scan));
  const auto map = [&](auto f) {
    auto out = given;
    for (auto& [n, p] : out) p = f(p);
    return out;
  };
  const auto ras = diagnose_landmark_frame(map([](const Vec3& p) { return Vec3(-p.x(), -p.y(), p.z()); }), scan);
  ASSERT_TRUE(ras);
  EXPECT_NE(ras->mistake.find("RAS read as LPS"), std::string::npos) << ras->mistake;
  EXPECT_LT(ras->corrected_median_mm, 5.0);
  const auto metres = diagnose_landmark_frame(map([](const Vec3& p) { return Vec3(p / 1000.0); }), scan);
  ASSERT_TRUE(metres);
  EXPECT_NE(metres->mistake.find("in metres but read as millimetres"), std::string::npos) << metres->mistake;
  const auto both = diagnose_landmark_frame(map([](const Vec3& p) { return Vec3(-p.x() / 1000.0, -p.y() / 1000.0, p.z() / 1000.0); }), scan);
  ASSERT_TRUE(both);
  EXPECT_NE(both->mistake.find("negated and in metres"), std::string::npos) << both->mistake;
}

}  // namespace
}  // namespace breastfit::pipeline
