// Automatic landmarks on a synthetic scan: every template landmark, on the scan, near the truth.
#include "breastfit/pipeline/detect_landmarks.h"

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"
#include "breastfit/synth/synth_case.h"
#include "support/default_template.h"

namespace breastfit::pipeline {
namespace {

TEST(DetectLandmarks, FindsEveryLandmarkOnTheScanNearTheTruth) {
  synth::SynthOptions o;
  o.seed = 12;
  o.misalign_rotation_deg = 150;
  const synth::SynthCase c = synth::make_case(*test::default_template(), o);
  RegisterRequest req;
  req.scan = c.scan;
  req.model = test::default_template();
  req.landmarks = LandmarkSet{};  // ignored
  const DetectedLandmarks d = detect_landmarks(req);
  ASSERT_EQ(d.landmarks.size(), test::default_template()->landmarks.size());
  EXPECT_EQ(d.registration.fit.summary.initialization, "landmark-free");
  double sum = 0;
  int n = 0;
  for (const auto& l : d.landmarks) {
    EXPECT_GE(l.confidence, 0.0) << l.name;
    EXPECT_LE(l.confidence, 1.0) << l.name;
    if (l.name == "nipple_R" || l.name == "nipple_L") EXPECT_EQ(l.method, "breast tip on the scan");
    const bool lowest = l.name == "lowest_breast_R" || l.name == "lowest_breast_L";
    if (lowest) EXPECT_EQ(l.method, "breast fold on the scan") << l.name;
    if (l.name == "sternal_notch") EXPECT_EQ(l.method, "jugular notch on the scan");
    const bool fitted_or_proportion =
        l.method == "fitted template, snapped to the scan" || l.method == "sternum's proportions on the scan";
    if (l.name.rfind("pectoral_insertion_", 0) == 0)
      EXPECT_TRUE(l.method.rfind("anterior axillary fold on the scan", 0) == 0 || fitted_or_proportion)
          << l.name << ": " << l.method;
    if (l.name.rfind("acromion_", 0) == 0 || l.name.rfind("midaxillary_", 0) == 0)
      EXPECT_TRUE(fitted_or_proportion) << l.name << ": " << l.method;
    for (const auto& t : c.truth_landmarks)
      if (t.name == l.name) {
        sum += (l.position_mm - t.position).norm();
        ++n;
        // The refine stage holds them at the benchmark torsos' proportions (fit/breast_fold.h); this
        // template-made torso's own lowest breast points lie 24 mm from where those put them.
        if (lowest) EXPECT_LT((l.position_mm - t.position).norm(), 30.0) << l.name;
      }
  }
  ASSERT_GT(n, 0);
  EXPECT_LT(sum / n, 30.0);
  EXPECT_EQ(to_markups(d.landmarks).points.size(), d.landmarks.size());
}

// On a prepared scan (the workstation's open scan): the same landmarks as from the scan itself,
// every iteration seen, and an aborted fit is an error, not landmarks.
TEST(DetectLandmarks, OnAPreparedScanTheSameAndAbortable) {
  synth::SynthOptions o;
  o.seed = 4;
  const synth::SynthCase c = synth::make_case(*test::default_template(), o);
  RegisterRequest req;
  req.scan = c.scan;
  req.model = test::default_template();
  const DetectedLandmarks direct = detect_landmarks(req);
  PreparedTarget target = prepare_target(c.scan, "scan", std::nullopt, req.options);
  int iterations = 0;
  const DetectedLandmarks prepared = detect_landmarks(req, target, [&](const fit::IterationRecord&) {
    ++iterations;
    return fit::CallbackResult::Continue;
  });
  EXPECT_GT(iterations, 0);
  ASSERT_EQ(prepared.landmarks.size(), direct.landmarks.size());
  for (size_t k = 0; k < direct.landmarks.size(); ++k) {
    EXPECT_EQ(prepared.landmarks[k].name, direct.landmarks[k].name);
    EXPECT_LT((prepared.landmarks[k].position_mm - direct.landmarks[k].position_mm).norm(), 1e-6) << direct.landmarks[k].name;
    EXPECT_NEAR(prepared.landmarks[k].confidence, direct.landmarks[k].confidence, 1e-9);
  }
  EXPECT_THROW(detect_landmarks(req, target, [](const fit::IterationRecord&) { return fit::CallbackResult::Abort; }),
               InvalidInput);
}

}  // namespace
}  // namespace breastfit::pipeline
