// The problem's correspondences: a saved state given back after a detour through other poses is
// kept by the next search at its pose and arguments (the landmark check's re-linearised
// predictions), and it is the state a search there finds.
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

TEST(Problem, RestoredCorrespondencesAreKeptAtTheirPose) {
  const model::RiggedModel& model = *test::default_template();
  // The scan: the template at rest, moved 2 mm; the model posed at rest and 6 mm away.
  TriangleMesh scan_mesh = model.rest;
  scan_mesh.V.col(1).array() += 2.0;
  ScanTarget scan(scan_mesh, 300);
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

}  // namespace
}  // namespace breastfit::fit
