#include "breastfit/serve/scan_session.h"

#include <gtest/gtest.h>

#include <cmath>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/pipeline/fit_deviation.h"
#include "breastfit/synth/synth_case.h"
#include "breastfit/transfer/breast_measurements.h"
#include "support/default_template.h"
#include "support/test_paths.h"

namespace breastfit::serve {
namespace {

struct Case {
  std::filesystem::path scan = test::temp_dir() / "scan.ply";
  LandmarkSet landmarks;
  Case() {
    synth::SynthOptions o;
    o.seed = 11;
    const synth::SynthCase c = synth::make_case(*test::default_template(), o);
    io::write_mesh(scan, c.scan);
    landmarks.points = c.input_landmarks;
    landmarks.declared_units = "mm";
  }
};

const Case& the_case() {
  static const Case c;
  return c;
}

TEST(ScanSession, WarmRefitStartsFromThePreviousFit) {
  ScanSession s("1", the_case().scan, "scan.ply", test::default_template());
  EXPECT_GT(s.scan().mesh_mm.F.rows(), 0);
  const auto cold = s.run_fit(the_case().landmarks, true);  // nothing to warm-start from yet
  ASSERT_TRUE(cold->result.usable()) << cold->result.fit.summary.message;
  EXPECT_FALSE(cold->warm);
  EXPECT_EQ(cold->generation, 1);
  EXPECT_EQ(cold->distances_mm.size(), static_cast<size_t>(cold->result.fit.vertices.rows()));

  LandmarkSet moved = the_case().landmarks;
  moved.points[8].position.z() += 3.0;
  const auto warm = s.run_fit(moved, true);
  ASSERT_TRUE(warm->result.usable());
  EXPECT_TRUE(warm->warm);
  EXPECT_EQ(warm->result.fit.summary.initialization, "warm start");
  ASSERT_EQ(warm->result.fit.summary.stages.size(), 1u);
  EXPECT_EQ(warm->result.fit.summary.stages[0].name, "refine");
  EXPECT_LT(warm->result.fit.summary.iterations.size(), cold->result.fit.summary.iterations.size());
  // Close to the full fit: the mean surface error does not get worse by more than a tenth of a mm.
  EXPECT_LT(warm->result.surface.mae, cold->result.surface.mae + 0.1);
}

// The re-fit's fast path (fit::RefitOptions: final threshold from the start, 2 iterations, stop on
// small steps) after a 10 mm move lies no farther from a full fit from scratch with the moved
// landmark than the whole refine stage's re-fit does, beyond 0.3 mm (median vertex) and 1 mm
// (farthest drawing point); and its surface stays within half a millimetre (median vertex) of that
// re-fit's.
TEST(ScanSession, FastRefitStaysAsCloseToTheColdFitAsTheWholeRefine) {
  fit::FitOptions whole;
  whole.refit.final_threshold = false;
  whole.refit.max_iterations = whole.refine.max_iterations;
  whole.refit.vertex_tolerance_mm = 0;
  ScanSession fast_session("1", the_case().scan, "scan.ply", test::default_template());
  ScanSession whole_session("2", the_case().scan, "scan.ply", test::default_template(), whole);
  ASSERT_TRUE(fast_session.run_fit(the_case().landmarks, false)->result.usable());
  ASSERT_TRUE(whole_session.run_fit(the_case().landmarks, false)->result.usable());
  LandmarkSet moved = the_case().landmarks;
  moved.points[8].position.x() += 10.0;
  const auto fast = fast_session.run_fit(moved, true);
  const auto full_refine = whole_session.run_fit(moved, true);
  const auto cold = whole_session.run_fit(moved, false);
  ASSERT_TRUE(fast->warm && full_refine->warm && !cold->warm);
  ASSERT_TRUE(fast->result.usable() && full_refine->result.usable() && cold->result.usable());
  EXPECT_LT(fast->result.fit.summary.iterations.size(), full_refine->result.fit.summary.iterations.size());
  const pipeline::FitDeviation fast_cold = pipeline::fit_deviation(fast->result, cold->result);
  const pipeline::FitDeviation whole_cold = pipeline::fit_deviation(full_refine->result, cold->result);
  EXPECT_LE(fast_cold.surface_median_mm, whole_cold.surface_median_mm + 0.3);
  EXPECT_LE(fast_cold.drawings_max_mm, whole_cold.drawings_max_mm + 1.0);
  EXPECT_LE(pipeline::fit_deviation(fast->result, full_refine->result).surface_median_mm, 0.5);
}

// A re-fit is the same with 1 and 2 threads (its drawings beside its distances, then its landmark
// checks beside the breast volumes), and the session's breast-volume cache, warm from the
// first fit, changes nothing: the volumes are those measured without a cache.
TEST(ScanSession, RefitIsTheSameWithOneAndTwoThreads) {
  fit::FitOptions one, two;
  one.threads = 1;
  two.threads = 2;
  ScanSession s1("1", the_case().scan, "scan.ply", test::default_template(), one);
  ScanSession s2("2", the_case().scan, "scan.ply", test::default_template(), two);
  LandmarkSet moved = the_case().landmarks;
  moved.points[2].position.y() += 10.0;
  ASSERT_TRUE(s1.run_fit(the_case().landmarks, false)->result.usable());
  ASSERT_TRUE(s2.run_fit(the_case().landmarks, false)->result.usable());
  const auto a = s1.run_fit(moved, true);
  const auto b = s2.run_fit(moved, true);
  ASSERT_TRUE(a->warm && b->warm);
  const pipeline::RegisterResult &ra = a->result, &rb = b->result;
  EXPECT_EQ(rb.fit.vertices, ra.fit.vertices);
  EXPECT_EQ(rb.warnings, ra.warnings);
  ASSERT_TRUE(ra.breasts.right.volume_ml && rb.breasts.right.volume_ml && ra.breasts.left.volume_ml);
  EXPECT_EQ(*rb.breasts.right.volume_ml, *ra.breasts.right.volume_ml);
  EXPECT_EQ(*rb.breasts.left.volume_ml, *ra.breasts.left.volume_ml);
  const transfer::BreastMeasurements uncached = transfer::measure_breasts(*test::default_template(), ra.fit.vertices);
  EXPECT_EQ(uncached.right.volume_ml, ra.breasts.right.volume_ml);
  EXPECT_EQ(uncached.left.volume_ml, ra.breasts.left.volume_ml);
  ASSERT_EQ(rb.fit.summary.landmark_checks.size(), ra.fit.summary.landmark_checks.size());
  for (size_t i = 0; i < ra.fit.summary.landmark_checks.size(); ++i)
    EXPECT_EQ(rb.fit.summary.landmark_checks[i].predicted_distance_mm,
              ra.fit.summary.landmark_checks[i].predicted_distance_mm) << i;
  EXPECT_EQ(rb.surface.mae, ra.surface.mae);
  EXPECT_EQ(rb.surface_model_only.mae, ra.surface_model_only.mae);
  EXPECT_EQ(rb.breasts.warnings, ra.breasts.warnings);
  EXPECT_EQ(rb.breasts.volume_ratio, ra.breasts.volume_ratio);
  ASSERT_EQ(rb.drawings_on_scan.size(), ra.drawings_on_scan.size());
  for (size_t i = 0; i < ra.drawings_on_scan.size(); ++i)
    EXPECT_EQ(rb.drawings_on_scan[i].points, ra.drawings_on_scan[i].points) << ra.drawings_on_scan[i].name;
}

// A re-fit's first result (what the page shows at once): the fitted model and drawings of the
// whole re-fit, without the landmark checks, distances and breast measurements, which follow; the
// whole outcome is the same as a re-fit without a first result. A fit from scratch has none.
TEST(ScanSession, RefitShowsTheModelAndDrawingsFirst) {
  ScanSession s("1", the_case().scan, "scan.ply", test::default_template());
  ScanSession plain("2", the_case().scan, "scan.ply", test::default_template());
  std::vector<std::shared_ptr<const FitOutcome>> firsts;
  auto keep = [&](std::shared_ptr<const FitOutcome> f) { firsts.push_back(std::move(f)); };
  ASSERT_TRUE(s.run_fit(the_case().landmarks, false, keep)->result.usable());
  ASSERT_TRUE(plain.run_fit(the_case().landmarks, false)->result.usable());
  EXPECT_TRUE(firsts.empty());
  LandmarkSet moved = the_case().landmarks;
  moved.points[3].position.x() += 10.0;
  const auto whole = s.run_fit(moved, true, keep);
  const auto reference = plain.run_fit(moved, true);
  ASSERT_EQ(firsts.size(), 1u);
  const FitOutcome& first = *firsts[0];
  EXPECT_FALSE(first.complete);
  EXPECT_TRUE(whole->complete);
  EXPECT_EQ(first.generation, whole->generation);
  EXPECT_TRUE(first.warm);
  EXPECT_LE(first.surface_ms, whole->server_ms);
  EXPECT_EQ(first.surface_ms, whole->surface_ms);
  EXPECT_EQ(first.result.fit.vertices, whole->result.fit.vertices);
  EXPECT_EQ(first.result.model_landmarks_mm.points.size(), whole->result.model_landmarks_mm.points.size());
  ASSERT_EQ(first.result.drawings_on_scan.size(), whole->result.drawings_on_scan.size());
  for (size_t i = 0; i < first.result.drawings_on_scan.size(); ++i)
    EXPECT_EQ(first.result.drawings_on_scan[i].points, whole->result.drawings_on_scan[i].points);
  EXPECT_TRUE(first.distances_mm.empty());  // they follow
  EXPECT_EQ(whole->distances_mm.size(), static_cast<size_t>(whole->result.fit.vertices.rows()));
  EXPECT_EQ(first.result.scan.mesh_mm.V.rows(), 0);  // not copied
  EXPECT_TRUE(first.result.fit.summary.landmark_checks.empty());  // they follow
  EXPECT_FALSE(first.result.breasts.right.volume_ml.has_value());
  EXPECT_EQ(whole->result.fit.summary.landmark_checks.size(), moved.points.size());
  // The same whole outcome as without a first result.
  EXPECT_EQ(whole->result.fit.vertices, reference->result.fit.vertices);
  EXPECT_EQ(whole->result.warnings, reference->result.warnings);
  EXPECT_EQ(whole->result.breasts.right.volume_ml, reference->result.breasts.right.volume_ml);
  EXPECT_EQ(whole->result.breasts.left.volume_ml, reference->result.breasts.left.volume_ml);
  EXPECT_EQ(whole->result.surface_model_only.mae, reference->result.surface_model_only.mae);
  EXPECT_EQ(whole->result.status(), reference->result.status());
}

TEST(ScanSession, OneFitAtATimeAndCancel) {
  fit::FitOptions o;
  o.solver.function_tolerance = 1e-300;
  o.solver.gradient_tolerance = o.solver.parameter_tolerance = 0;
  for (auto* st : o.stages()) st->max_iterations = 400;
  ScanSession s("1", the_case().scan, "scan.ply", test::default_template(), o);
  ASSERT_TRUE(s.start_fit(the_case().landmarks, false));
  EXPECT_FALSE(s.start_fit(the_case().landmarks, false));
  EXPECT_EQ(s.status().state, FitState::Running);
  int used = 0;
  EXPECT_FALSE(s.with_target([&](const fit::ScanTarget&) { ++used; }));  // the fit owns the index
  s.cancel();
  s.wait();
  EXPECT_TRUE(s.with_target([&](const fit::ScanTarget& t) { used += t.mesh().F.rows() > 0; }));
  EXPECT_EQ(used, 1);
  const FitStatus st = s.status();
  EXPECT_EQ(st.state, FitState::Cancelled);
  EXPECT_EQ(st.outcome, nullptr);
  EXPECT_LT(st.iterations, 5 * 400);
}

TEST(ScanSession, SuggestsTheLandmarksOnTheOpenScan) {
  ScanSession s("1", the_case().scan, "scan.ply", test::default_template());
  ASSERT_TRUE(s.start_suggest());
  EXPECT_FALSE(s.start_fit(the_case().landmarks, false));  // one job at a time
  EXPECT_FALSE(s.start_suggest());
  EXPECT_EQ(s.status().job, "suggest");
  s.wait();
  const FitStatus st = s.status();
  ASSERT_EQ(st.state, FitState::Done) << st.message;
  ASSERT_NE(st.suggestion, nullptr);
  EXPECT_EQ(st.outcome, nullptr);  // a suggestion is not a fit
  ASSERT_EQ(st.suggestion->landmarks.size(), s.model().landmarks.size());
  EXPECT_GT(st.iterations, 0);
  EXPECT_GT(st.suggestion->server_ms, 0);
  for (const auto& d : st.suggestion->landmarks) {
    EXPECT_GE(d.confidence, 0.0);
    EXPECT_LE(d.confidence, 1.0);
    EXPECT_FALSE(d.method.empty());
  }
  // The suggested landmarks fit like the placed ones.
  LandmarkSet suggested;
  suggested.declared_units = "mm";
  for (const auto& d : st.suggestion->landmarks) suggested.points.push_back({d.name, d.position_mm});
  EXPECT_TRUE(s.run_fit(suggested, false)->result.usable());
}

TEST(ScanSession, ASuggestionCanBeCancelled) {
  ScanSession s("1", the_case().scan, "scan.ply", test::default_template());
  ASSERT_TRUE(s.start_suggest());
  s.cancel();
  s.wait();
  const FitStatus st = s.status();
  EXPECT_EQ(st.state, FitState::Cancelled) << st.message;
  EXPECT_EQ(st.suggestion, nullptr);
  EXPECT_NE(st.message.find("no landmarks"), std::string::npos) << st.message;
}

TEST(ScanSession, WaitStatusReturnsOnAChange) {
  ScanSession s("1", the_case().scan, "scan.ply", test::default_template());
  const uint64_t seen = s.status().version;
  EXPECT_EQ(s.wait_status(seen, std::chrono::milliseconds(1)).version, seen);  // nothing changed: the timeout
  ASSERT_TRUE(s.start_suggest());
  EXPECT_GT(s.wait_status(seen, std::chrono::seconds(60)).version, seen);
  s.wait();
}

TEST(ScanSession, BadInputsAreReported) {
  EXPECT_THROW(ScanSession("1", test::temp_dir() / "none.ply", "none.ply", test::default_template()), IoError);
  ScanSession s("1", the_case().scan, "scan.ply", test::default_template());
  LandmarkSet bad;
  bad.points = {{"belly_button", Vec3(0, 0, 0)}};
  bad.declared_units = "mm";
  ASSERT_TRUE(s.start_fit(bad, false));
  s.wait();
  EXPECT_EQ(s.status().state, FitState::Failed);
  EXPECT_NE(s.status().message.find("belly_button"), std::string::npos) << s.status().message;
}

}  // namespace
}  // namespace breastfit::serve
