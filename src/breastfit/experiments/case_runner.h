#pragma once
/// \file Registers one loaded case many times (one per experiment configuration) and scores
/// each fit: the paper's errors and, when the case has truth, the errors against it. What is
/// the same for every run of the case (the truth's closest-point index, the scan in mm for the
/// "observed" test) is built once.
#include <functional>
#include <memory>

#include "breastfit/experiments/case_set.h"
#include "breastfit/experiments/run_record.h"
#include "breastfit/fit/fit_options.h"
#include "breastfit/model/rigged_model.h"
#include "breastfit/pipeline/register_scan.h"

namespace breastfit::experiments {

/// The run record's status of a registration: "ok" when usable, else "not_usable" when the
/// solver converged (the verdict rejected the fit) or "not_converged" when it did not.
std::string run_status(const fit::FitSummary& summary);

class CaseRunner {
 public:
  /// Keeps a reference to `c` (must outlive the runner). \throws InvalidInput for a scan that
  /// cannot be registered at all (not a torso, no triangles).
  explicit CaseRunner(const EvalCase& c);
  ~CaseRunner();

  const EvalCase& eval_case() const { return case_; }

  /// One registration with `options`, scored. Never throws for a failed registration: an
  /// exception becomes status "error" with its message, a flagged fit "not_converged" (still
  /// scored). `on_result` (optional) sees the full result of a registration that ran (e.g. to
  /// write its outputs for the external referee).
  RunRecord run(const model::RiggedModel& model, const fit::FitOptions& options,
                const std::function<void(const pipeline::RegisterResult&)>& on_result = {}) const;

  /// Scores a registration result of this case (what run() does after registering).
  RunRecord score(const pipeline::RegisterResult& result) const;

 private:
  struct Reference;
  const EvalCase& case_;
  std::unique_ptr<Reference> ref_;
};

}  // namespace breastfit::experiments
