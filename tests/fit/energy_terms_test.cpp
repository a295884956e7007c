// One finite-difference gradient test per energy term of the table (fit/energy_terms.h), at fixed
// correspondences and sliding-landmark choices, on the toy model; plus the table's own rules.
#include "breastfit/fit/energy_terms.h"

#include <set>

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"
#include "breastfit/fit/problem.h"
#include "breastfit/fit/registration.h"
#include "breastfit/model/param_layout.h"
#include "support/toy_model.h"

namespace breastfit::fit {
namespace {

// The toy model with a sliding landmark (lowest point of its breast_R region) added.
const model::RiggedModel& toy_with_sliding_landmark() {
  static const model::RiggedModel m = [] {
    model::RiggedModel t = test::make_toy_model();
    t.landmarks.push_back({"lowest_breast_R", t.landmarks[1].point});
    return t;
  }();
  return m;
}

struct TermSetup {
  const model::RiggedModel& m = toy_with_sliding_landmark();
  model::PoseParams truth = test::random_toy_pose(m, 11, 0.6);
  model::PoseParams start = test::random_toy_pose(m, 12, 0.3);
  ScanTarget scan{[&] {
                    TriangleMesh t;
                    t.V = model::pose_vertices(m, truth);
                    t.F = m.rest.F;
                    return t;
                  }(),
                  300};
  FitOptions options = [] {
    FitOptions o;
    o.correspondences.kernel = RobustKernel::Huber;
    o.correspondences.point_to_point_weight = 0.3;  // both rows of the data term
    return o;
  }();
  std::vector<LandmarkTarget> landmarks() const {
    const Points V = model::pose_vertices(m, truth);
    std::vector<std::pair<std::string, Vec3>> named;
    for (const auto& lm : m.landmarks) named.emplace_back(lm.name, lm.point.position(V, m.rest.F) + Vec3(1, -2, 3));
    return match_landmarks(m, named);
  }
};

class EnergyTermGradient : public ::testing::TestWithParam<std::string> {};

TEST_P(EnergyTermGradient, MatchesCentralFiniteDifferences) {
  const std::string name = GetParam();
  TermSetup s;
  Problem problem(s.m, s.scan, s.options, s.landmarks());
  problem.evaluator().set_params(s.start);
  problem.update_correspondences(1e6, 1, true);
  problem.update_terms();
  const auto& layout = problem.evaluator().layout();
  NormalEquations eq(layout.num_params());
  const double e = problem.evaluate_term(name, &eq);
  eq.finalize();
  ASSERT_GT(e, 0.0) << "the test pose must give the term some energy";
  ASSERT_GT(eq.g().cwiseAbs().maxCoeff(), 0.0);
  // The cost is Σ w r²: its gradient is 2 Jᵀ W r = 2 g.
  const double h = 1e-6;
  int checked = 0;
  for (int i = 0; i < layout.num_params(); ++i) {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(layout.num_params());
    d[i] = h;
    auto plus = s.start, minus = s.start;
    layout.apply_increment(s.m, d, plus);
    layout.apply_increment(s.m, -d, minus);
    problem.evaluator().set_params(plus);
    const double ep = problem.evaluate_term(name, nullptr);
    problem.evaluator().set_params(minus);
    const double em = problem.evaluate_term(name, nullptr);
    const double fd = (ep - em) / (2 * h);
    EXPECT_NEAR(2 * eq.g()[i], fd, 1e-4 * std::max(1.0, std::abs(fd))) << name << " / " << layout.name(i);
    checked += std::abs(fd) > 1e-8 ? 1 : 0;
  }
  EXPECT_GT(checked, 0) << name << ": no parameter moves the term";
}

std::vector<std::string> term_names() {
  std::vector<std::string> names;
  for (const auto& t : energy_terms()) names.emplace_back(t.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(EveryTerm, EnergyTermGradient, ::testing::ValuesIn(term_names()),
                         [](const auto& info) { return info.param; });

TEST(EnergyTerms, TableHasUniqueNamesPositiveDefaultsAndFactories) {
  std::set<std::string_view> names;
  for (const auto& t : energy_terms()) {
    EXPECT_TRUE(names.insert(t.name).second) << t.name;
    EXPECT_GT(t.default_lambda, 0.0) << t.name;
    EXPECT_FALSE(t.help.empty()) << t.name;
    ASSERT_NE(t.make, nullptr) << t.name;
    EXPECT_NE(t.make(), nullptr) << t.name;
    EXPECT_EQ(find_energy_term(t.name), &t);
  }
  EXPECT_EQ(find_energy_term("nonsense"), nullptr);
  EXPECT_EQ(energy_terms().size(), 8u);
}

TEST(EnergyTerms, TheBreakdownIsTheSumOfTheTermsInTableOrder) {
  TermSetup s;
  Problem problem(s.m, s.scan, s.options, s.landmarks());
  problem.evaluator().set_params(s.start);
  problem.update_correspondences(1e6, 1, true);
  problem.update_terms();
  const EnergyBreakdown e = problem.evaluate(nullptr);
  ASSERT_EQ(e.terms.size(), energy_terms().size());
  double sum = 0;
  for (size_t i = 0; i < e.terms.size(); ++i) {
    EXPECT_EQ(e.terms[i].first, energy_terms()[i].name);
    EXPECT_DOUBLE_EQ(e.terms[i].second, problem.evaluate_term(e.terms[i].first, nullptr));
    sum += e.terms[i].second;
  }
  EXPECT_NEAR(e.total(), sum, 1e-12 * sum);
}

TEST(EnergyTerms, ADisabledTermContributesNothing) {
  TermSetup s;
  s.options.weights.set_lambda("reverse", 0.0);
  Problem problem(s.m, s.scan, s.options, s.landmarks());
  problem.evaluator().set_params(s.start);
  problem.update_correspondences(1e6, 1, true);
  EXPECT_EQ(problem.evaluate(nullptr)["reverse"], 0.0);
  EXPECT_EQ(problem.evaluate_term("reverse", nullptr), 0.0);
  EXPECT_THROW(problem.evaluate_term("nonsense", nullptr), InvalidInput);
}

TEST(EnergyTerms, LambdaScalesTheTermInversely) {
  TermSetup s;
  Problem a(s.m, s.scan, s.options, s.landmarks());
  s.options.weights.set_lambda("scale", s.options.weights.lambda("scale") * 4);
  Problem b(s.m, s.scan, s.options, s.landmarks());
  a.evaluator().set_params(s.start);
  b.evaluator().set_params(s.start);
  EXPECT_NEAR(a.evaluate_term("scale", nullptr), 4 * b.evaluate_term("scale", nullptr),
              1e-12 * a.evaluate_term("scale", nullptr));
}

TEST(SlidingLandmarkTerm, FollowsTheLowestPointOfTheRegionAfterAnUpdate) {
  TermSetup s;
  Problem problem(s.m, s.scan, s.options, s.landmarks());
  problem.evaluator().set_params(s.start);
  const double before = problem.evaluate_term("sliding_landmarks", nullptr);
  problem.update_terms();
  const double after = problem.evaluate_term("sliding_landmarks", nullptr);
  // The toy landmark's stored point is the nipple, not the region's lowest vertex: the update
  // must change which model point the term uses.
  EXPECT_NE(before, after);
}

}  // namespace
}  // namespace breastfit::fit
