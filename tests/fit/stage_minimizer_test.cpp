#include "breastfit/fit/stage_minimizer.h"

#include <gtest/gtest.h>

#include "breastfit/fit/registration.h"
#include "breastfit/model/pose_evaluator.h"
#include "support/toy_model.h"

namespace breastfit::fit {
namespace {

struct ToyCase : test::ToyScanCase {
  ToyCase() : ToyScanCase(21, 0.5) {}
  std::vector<LandmarkTarget> landmarks() const { return match_landmarks(m, named_landmarks()); }
};

TEST(StageMinimizer, AStageWithRoomToSpareEndsByConvergenceNotByItsCap) {
  ToyCase c;
  ScanTarget scan(c.mesh, 300);
  FitOptions o;
  Problem problem(c.m, scan, o, c.landmarks());
  model::PoseParams p = model::PoseParams::identity(c.m);
  p.global.translation = Vec3(3, -2, 4);
  StageOptions stage{"rigid", true, false, false, 200, 1};
  FitSummary s;
  const Termination t = minimize_stages(problem, {stage}, p, s);
  EXPECT_TRUE(is_convergence(t)) << to_string(t);
  ASSERT_EQ(s.stages.size(), 1u);
  EXPECT_LT(s.stages[0].iterations, 200);
  EXPECT_LT(s.stages[0].final_energy, s.stages[0].initial_energy);
  ASSERT_EQ(s.timings.size(), 1u);
  EXPECT_EQ(s.timings[0].phase, "stage:rigid");
}

TEST(StageMinimizer, StopsOnceAStepMovesNoVertexFartherThanTheVertexTolerance) {
  ToyCase c;
  ScanTarget scan(c.mesh, 300);
  StageOptions stage{"rigid", true, false, false, 200, 1};
  auto run = [&](double tolerance_mm) {
    FitOptions o;
    o.solver.function_tolerance = 1e-300;  // only the vertex tolerance (or the cap) ends the stage
    o.solver.gradient_tolerance = o.solver.parameter_tolerance = 0;
    o.solver.vertex_tolerance_mm = tolerance_mm;
    o.correspondences.max_distance_start_mm = o.correspondences.max_distance_end_mm;  // tests from iteration 1
    Problem problem(c.m, scan, o, c.landmarks());
    model::PoseParams p = model::PoseParams::identity(c.m);
    p.global.translation = Vec3(3, -2, 4);
    FitSummary s;
    const Termination t = minimize_stages(problem, {stage}, p, s);
    return std::make_pair(t, s.stages.at(0).iterations);
  };
  const auto [loose, loose_iterations] = run(0.5);
  const auto [tight, tight_iterations] = run(1e-3);
  EXPECT_EQ(loose, Termination::ParameterTolerance);
  EXPECT_LT(loose_iterations, tight_iterations);
  EXPECT_LT(tight_iterations, 200);
  const auto [off, off_iterations] = run(0);  // off: the other tests decide (here: the cap or no decrease)
  EXPECT_GE(off_iterations, tight_iterations);
}

TEST(StageMinimizer, AcceptedStepsNeverRaiseTheEnergyAtFixedCorrespondences) {
  ToyCase c;
  ScanTarget scan(c.mesh, 300);
  FitOptions o;
  Problem problem(c.m, scan, o, c.landmarks());
  model::PoseParams p = model::PoseParams::identity(c.m);
  FitSummary s;
  minimize_stages(problem, {o.landmark_pose, o.rigid, o.pose, o.shape}, p, s);
  ASSERT_FALSE(s.iterations.empty());
  for (const auto& r : s.iterations) {
    EXPECT_LE(r.energy_after, r.energy_before) << r.stage << " " << r.iteration;
    if (r.accepted) {
      EXPECT_GT(r.predicted_decrease, 0) << r.stage << " " << r.iteration;
      EXPECT_GE(r.gain_ratio, o.solver.min_gain_ratio);
    }
  }
}

TEST(StageMinimizer, ReFindsTheCorrespondencesEveryIntervalIterationsOnly) {
  ToyCase c;
  ScanTarget scan(c.mesh, 300);
  FitOptions o;
  model::PoseParams start = model::PoseParams::identity(c.m);
  start.global.translation = Vec3(3, -2, 4);
  StageOptions stage{"rigid", true, false, false, 8, 1};
  const auto run = [&](int interval) {
    stage.correspondence_interval = interval;
    Problem problem(c.m, scan, o, {});  // no landmarks: nothing else is re-chosen per iteration
    model::PoseParams p = start;
    FitSummary s;
    minimize_stages(problem, {stage}, p, s);
    return s.iterations;
  };
  const auto every = run(1), second = run(2);
  ASSERT_EQ(second.size(), 8u);
  EXPECT_NE(every[1].max_distance_mm, every[0].max_distance_mm);  // the threshold ramps down
  for (size_t it = 1; it < second.size(); it += 2) {
    // The pairs of the iteration before: same threshold, same count, the energy picks up where
    // the accepted step left it.
    EXPECT_EQ(second[it].max_distance_mm, second[it - 1].max_distance_mm) << it;
    EXPECT_EQ(second[it].kept, second[it - 1].kept) << it;
    if (second[it - 1].accepted) EXPECT_EQ(second[it].energy_before, second[it - 1].energy_after) << it;
  }
  EXPECT_NE(second[2].max_distance_mm, second[0].max_distance_mm);
}

TEST(StageMinimizer, TheCallbackCanAbortAndTheResultIsThenNotUsable) {
  ToyCase c;
  ScanTarget scan(c.mesh, 300);
  int calls = 0;
  const FitResult r = register_template(c.m, scan, c.landmarks(), FitOptions{}, [&](const IterationRecord&) {
    return ++calls == 3 ? CallbackResult::Abort : CallbackResult::Continue;
  });
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(r.summary.iterations.size(), 3u);
  EXPECT_EQ(r.summary.termination, Termination::Aborted);
  EXPECT_FALSE(r.summary.usable());
  EXPECT_NE(r.summary.message.find("aborted"), std::string::npos) << r.summary.message;
  EXPECT_FALSE(r.summary.detail.applied);
}

TEST(StageMinimizer, RecordsTheFitPhasesInOrder) {
  ToyCase c;
  ScanTarget scan(c.mesh, 300);
  // The toy's "breasts" are bumps without a tip to check the nipples against (landmark_check_test):
  // a nipple flagged by that check is held off and the refine stage runs again.
  FitOptions o;
  o.nipple_tip_check_mm = 1e3;
  const FitResult r = register_template(c.m, scan, c.landmarks(), o);
  ASSERT_TRUE(r.summary.usable()) << r.summary.message;
  std::vector<std::string> phases;
  double sum = 0;
  for (const auto& p : r.summary.timings) {
    phases.push_back(p.phase);
    EXPECT_GE(p.seconds, 0.0);
    sum += p.seconds;
  }
  EXPECT_EQ(phases, (std::vector<std::string>{"initialization", "stage:landmark_pose", "stage:rigid", "stage:pose",
                                              "stage:shape", "stage:refine", "final_state", "surface_detail",
                                              "landmark_checks"}));
  EXPECT_LE(sum, r.summary.seconds * 1.0001 + 1e-6);
}

TEST(StageMinimizer, IsDeterministic) {
  ToyCase c;
  ScanTarget a(c.mesh, 300), b(c.mesh, 300);
  const FitResult ra = register_template(c.m, a, c.landmarks(), FitOptions{});
  const FitResult rb = register_template(c.m, b, c.landmarks(), FitOptions{});
  EXPECT_EQ(ra.vertices, rb.vertices);
  EXPECT_EQ(ra.summary.iterations.size(), rb.summary.iterations.size());
}

}  // namespace
}  // namespace breastfit::fit
