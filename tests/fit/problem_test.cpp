// The problem's correspondences: a saved state given back after a detour through other poses is
// kept by the next search at its pose and arguments (the landmark check's re-linearised
// predictions), and it is the state a search there finds; the reverse term's pairs after other
// poses are a fresh search's.
#include "breastfit/fit/problem.h"

#include <gtest/gtest.h>

#include "breastfit/fit/scan_target.h"
#include "support/default_template.h"

namespace breastfit::fit {
namespace {

void expect_same_pairs(const std::vector<Correspondence>& a, const std::vector<Correspondence>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].vertex, b[k].vertex);
    EXPECT_EQ(a[k].target, b[k].target);
    EXPECT_EQ(a[k].weight, b[k].weight);
  }
}

// The scan of both tests: the template at rest, moved 2 mm.
ScanTarget template_moved_2mm(const model::RiggedModel& model) {
  TriangleMesh scan_mesh = model.rest;
  scan_mesh.V.col(1).array() += 2.0;
  return ScanTarget(scan_mesh, 300);
}

TEST(Problem, RestoredCorrespondencesAreKeptAtTheirPose) {
  const model::RiggedModel& model = *test::default_template();
  // The model posed at rest and 6 mm away.
  ScanTarget scan = template_moved_2mm(model);
  const FitOptions options;
  Problem problem(model, scan, options, {});
  const model::PoseParams rest = model::PoseParams::identity(model);
  model::PoseParams moved = rest;
  moved.global.translation = Vec3(0.0, 6.0, 0.0);

  problem.evaluator().set_params(rest);
  problem.update_correspondences(15.0, 1, true);
  const Problem::CorrespondenceState at_rest = problem.correspondence_state();
  ASSERT_GT(at_rest.pairs.size(), 1000u);
  ASSERT_GT(at_rest.reverse_pairs.size(), 100u);

  problem.evaluator().set_params(moved);
  problem.update_correspondences(15.0, 1, true);
  ASSERT_NE(problem.pairs().front().target, at_rest.pairs.front().target);

  // Given back at its pose: the same pairs as a fresh problem's search there.
  problem.evaluator().set_params(rest);
  problem.restore_correspondences(at_rest);
  problem.update_correspondences(15.0, 1, true);
  Problem fresh(model, scan, options, {});
  fresh.evaluator().set_params(rest);
  fresh.update_correspondences(15.0, 1, true);
  expect_same_pairs(problem.pairs(), fresh.pairs());
  EXPECT_EQ(problem.reverse_pairs().size(), fresh.reverse_pairs().size());
  EXPECT_EQ(problem.stats().kept, fresh.stats().kept);

  // Kept without a search (a tampered state survives) at its pose and arguments only.
  Problem::CorrespondenceState tampered = at_rest;
  tampered.pairs.pop_back();
  problem.restore_correspondences(tampered);
  problem.update_correspondences(15.0, 1, true);
  EXPECT_EQ(problem.pairs().size(), at_rest.pairs.size() - 1);
  problem.update_correspondences(15.0, 2, true);  // another stride: searched again
  EXPECT_EQ(problem.stats().candidates, (model.num_vertices() + 1) / 2);
  problem.restore_correspondences(tampered);
  problem.evaluator().set_params(moved);
  problem.update_correspondences(15.0, 1, true);  // another pose: searched again
  EXPECT_EQ(problem.stats().candidates, model.num_vertices());
  EXPECT_NE(problem.pairs().front().target, at_rest.pairs.front().target);
}

// The reverse term's pairs at a pose reached through others (the posed model's index moved from
// pose to pose, not built anew) are those of a fresh problem searching there first.
TEST(Problem, ReversePairsAfterOtherPosesAreThoseOfAFreshSearch) {
  const model::RiggedModel& model = *test::default_template();
  ScanTarget scan = template_moved_2mm(model);
  const FitOptions options;
  Problem problem(model, scan, options, {});
  model::PoseParams pose = model::PoseParams::identity(model);
  for (const double y : {0.0, 6.0, -3.0}) {  // the arms and the shape unchanged: the translation only
    pose.global.translation = Vec3(0.5 * y, y, 0.0);
    problem.evaluator().set_params(pose);
    problem.update_correspondences(15.0, 1, true);
  }
  pose.global.scale *= 1.03;  // and a last pose reached by scaling
  problem.evaluator().set_params(pose);
  problem.update_correspondences(15.0, 1, true);
  Problem fresh(model, scan, options, {});
  fresh.evaluator().set_params(pose);
  fresh.update_correspondences(15.0, 1, true);
  const auto& a = problem.reverse_pairs();
  const auto& b = fresh.reverse_pairs();
  ASSERT_GT(b.size(), 100u);
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].source, b[k].source);
    EXPECT_EQ(a[k].model_point.face, b[k].model_point.face);
    EXPECT_EQ(a[k].model_point.bary, b[k].model_point.bary);
    EXPECT_EQ(a[k].weight, b[k].weight);
  }
  EXPECT_EQ(problem.reverse_stats().rejected_normal, fresh.reverse_stats().rejected_normal);
  EXPECT_EQ(problem.reverse_stats().rejected_boundary, fresh.reverse_stats().rejected_boundary);
}

}  // namespace
}  // namespace breastfit::fit
