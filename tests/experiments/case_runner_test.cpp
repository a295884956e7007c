// The status a run record gets from a registration's summary: a converged fit that the verdict
// rejects is "not_usable", never "not_converged".
#include <gtest/gtest.h>

#include "breastfit/experiments/case_runner.h"

namespace breastfit::experiments {
namespace {

fit::FitSummary summary(fit::Termination t, bool usable) {
  fit::FitSummary s;
  s.termination = t;
  s.verdict.usable = usable;
  return s;
}

TEST(CaseRunner, RunStatusSaysNotConvergedOnlyWhenTheSolverDidNotConverge) {
  using T = fit::Termination;
  for (T t : {T::FunctionTolerance, T::GradientTolerance, T::ParameterTolerance, T::NoFurtherDecrease}) {
    EXPECT_EQ(run_status(summary(t, true)), "ok");
    EXPECT_EQ(run_status(summary(t, false)), "not_usable") << fit::to_string(t);
  }
  EXPECT_EQ(run_status(summary(T::IterationCap, true)), "ok");  // a usable fit at its cap
  for (T t : {T::IterationCap, T::Aborted, T::NumericalFailure})
    EXPECT_EQ(run_status(summary(t, false)), "not_converged") << fit::to_string(t);
}

}  // namespace
}  // namespace breastfit::experiments
