#include "breastfit/fit/fit_summary.h"

#include <set>

#include <gtest/gtest.h>

namespace breastfit::fit {
namespace {

TEST(FitSummary, TerminationNamesAreDistinctAndConvergenceIsKnown) {
  std::set<std::string> names;
  int converged = 0;
  for (Termination t : {Termination::FunctionTolerance, Termination::GradientTolerance,
                        Termination::ParameterTolerance, Termination::NoFurtherDecrease, Termination::IterationCap,
                        Termination::Aborted, Termination::NumericalFailure}) {
    EXPECT_TRUE(names.insert(to_string(t)).second) << to_string(t);
    converged += is_convergence(t) ? 1 : 0;
  }
  EXPECT_EQ(converged, 4);
  EXPECT_FALSE(is_convergence(Termination::IterationCap));
}

TEST(FitSummary, KeepsTheVerdictApartFromTheTermination) {
  FitSummary s;
  s.termination = Termination::IterationCap;
  s.verdict = {true, "usable: fine"};
  EXPECT_TRUE(s.usable());
  EXPECT_FALSE(s.converged());
  s.termination = Termination::FunctionTolerance;
  s.verdict = {false, "not usable: far"};
  EXPECT_FALSE(s.usable());
  EXPECT_TRUE(s.converged());
  EXPECT_NE(s.brief().find("NOT USABLE (function_tolerance)"), std::string::npos) << s.brief();
}

TEST(EnergyBreakdown, SumsAndLooksUpByName) {
  EnergyBreakdown e;
  e.terms = {{"data", 1.5}, {"scale", 0.25}};
  EXPECT_DOUBLE_EQ(e.total(), 1.75);
  EXPECT_DOUBLE_EQ(e["scale"], 0.25);
  EXPECT_DOUBLE_EQ(e["nothing"], 0.0);
}

TEST(FitSummary, TimesPhasesByName) {
  FitSummary s;
  s.timings = {{"initialization", 0.01}, {"stage:rigid", 0.02}};
  EXPECT_DOUBLE_EQ(s.phase_seconds("stage:rigid"), 0.02);
  EXPECT_DOUBLE_EQ(s.phase_seconds("surface_detail"), 0.0);
}

}  // namespace
}  // namespace breastfit::fit
