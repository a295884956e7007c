#pragma once
/// \file What a registration reports. Two things are kept apart:
///  - the **termination**: why the solver stopped (a convergence test, the iteration cap, the
///    caller aborted, a numerical failure) — how the optimisation ended;
///  - the **verdict**: whether the fitted template can be used (enough of it on the scan, close
///    enough) and why — what the result is worth. An iteration cap with a good fit is usable; a
///    converged fit on the wrong body part is not.
/// Plus per-iteration records, per-stage summaries, energies per term and time per phase.
/// JSON: fit_summary_json.h.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "breastfit/fit/correspondences.h"
#include "breastfit/fit/landmark_check.h"

namespace breastfit::fit {

/// Why a stage (or the whole solve) stopped.
enum class Termination {
  FunctionTolerance,   ///< converged: relative energy decrease below solver.function_tolerance
  GradientTolerance,   ///< converged: gradient below solver.gradient_tolerance
  ParameterTolerance,  ///< converged: step below solver.parameter_tolerance
  NoFurtherDecrease,   ///< converged: no damped step lowers the energy (with a fresh Hessian)
  IterationCap,        ///< the stage ran its max_iterations
  Aborted,             ///< the iteration callback asked to stop
  NumericalFailure,    ///< the energy became non-finite
};
/// "function_tolerance", "gradient_tolerance", "parameter_tolerance", "no_further_decrease",
/// "iteration_cap", "aborted", "numerical_failure".
const char* to_string(Termination t);
/// True for the four convergence tests.
bool is_convergence(Termination t);

/// Energy per term at one parameter set (each already divided by its λ), by term name in the
/// order of energy_terms.h.
struct EnergyBreakdown {
  std::vector<std::pair<std::string, double>> terms;
  double total() const;
  /// The term's energy, 0 when the breakdown has no such term.
  double operator[](const std::string& name) const;
};

struct IterationRecord {
  std::string stage;
  int iteration = 0;             ///< within the stage
  double energy_before = 0;      ///< with this iteration's correspondences
  double energy_after = 0;       ///< after the accepted step (= before if none accepted)
  double predicted_decrease = 0; ///< of the accepted (or last tried) step, by the Gauss–Newton model
  double gain_ratio = 0;         ///< actual / predicted decrease of that step
  double gradient_max = 0;       ///< max |(JᵀWr)_i| at the start of the iteration
  double max_distance_mm = 0;    ///< correspondence threshold
  int kept = 0;                  ///< kept model→scan correspondences
  double damping = 0;            ///< LM damping after the iteration
  double step_norm = 0;          ///< max-norm of the accepted step
  bool accepted = false;
  double seconds = 0;            ///< wall time of the iteration
};

struct StageSummary {
  std::string name;
  int iterations = 0;
  Termination termination = Termination::IterationCap;
  double initial_energy = 0, final_energy = 0;
  double seconds = 0;
};

/// The surface-detail layer (fit/surface_detail.h), when applied.
struct DetailSummary {
  bool applied = false;
  int kept = 0;                          ///< scan correspondences in its last pass
  double mean_abs_mm = 0, max_abs_mm = 0;  ///< offsets along the normals
};

/// Whether the result can be used, and why (or why not).
struct Verdict {
  bool usable = true;
  std::string reason;  ///< one line
};

/// Wall time of one phase of the work (fit phases, and the pipeline's around them).
struct PhaseTime {
  std::string phase;  ///< "scan_preparation", "index_build", "initialization", "stage:<name>", "surface_detail", "landmark_checks", ...
  double seconds = 0;
};

/// The landmark-free initialisation's choice (fit/orientation_search.h), for the report.
struct OrientationSummary {
  struct Candidate {
    std::string name;
    double score = 0;     ///< mm, lower is better
    bool refined = false; ///< scored after the arms and a brief pose fit
  };
  bool searched = false;          ///< false: initialised from landmarks
  std::string chosen;             ///< the kept hypothesis' name
  std::string runner_up;          ///< the best hypothesis turned ≥ 45° from it ("" when none)
  double margin = 0;              ///< (runner-up score − best) / best; ∞ when no runner-up
  bool confident = true;          ///< margin ≥ the threshold (below: a warning)
  std::string body_frame;         ///< how the scan's shape gave the body axes
  double arm_abduction_deg[2] = {0, 0};  ///< R, L
  std::string arm_pose;           ///< "arms hanging (standing)" / "arms abducted (supine, arm boards)"
  std::vector<Candidate> candidates;  ///< best first
};

struct FitSummary {
  Termination termination = Termination::IterationCap;  ///< the last stage's (or aborted / failure)
  std::string termination_message;  ///< one line: how the solver ended
  Verdict verdict;
  /// One line for the user: the verdict's reason when not usable, else the termination message.
  std::string message;
  std::vector<StageSummary> stages;
  std::vector<IterationRecord> iterations;
  EnergyBreakdown final_energy;
  CorrespondenceStats final_correspondences;          ///< model → scan, at the end
  CorrespondenceStats final_reverse_correspondences;  ///< scan → model, at the end
  double kept_mae_mm = 0;             ///< mean |point-to-plane| over the final kept pairs
  std::string initialization;         ///< "landmarks" or "landmark-free"
  /// One line on how the template was placed (printed by the CLI, in both reports).
  std::string initialization_detail;
  OrientationSummary orientation;     ///< landmark-free only
  /// Landmarks not given that were held at anatomy found on the scan after the pose stage (the
  /// nipples at the breast tips landmark-free, the lowest breast points at the folds): their count
  /// and names.
  int anatomical_landmarks = 0;
  std::vector<std::string> anatomical_landmark_names;
  int landmarks_used = 0;
  DetailSummary detail;
  std::vector<LandmarkCheck> landmark_checks;  ///< every landmark used, after the fit
  std::vector<std::string> warnings;
  std::vector<PhaseTime> timings;     ///< in order; the pipeline adds its own phases around the fit's
  /// The fit's own wall time: initialisation, stages and surface detail (register_template); the
  /// closest-point index is built before (its time is the "index_build" phase of `timings`).
  double seconds = 0;

  bool converged() const { return is_convergence(termination); }
  bool usable() const { return verdict.usable; }
  /// Seconds of the named phase (0 when absent).
  double phase_seconds(const std::string& phase) const;
  /// One line for the terminal.
  std::string brief() const;
};

/// What an iteration callback tells the solver.
enum class CallbackResult { Continue, Abort };

/// Called after every outer iteration (progress lines, cancel buttons). Returning Abort ends the
/// registration after this iteration: termination Aborted, verdict not usable, the parameters
/// reached so far returned.
using IterationCallback = std::function<CallbackResult(const IterationRecord&)>;

}  // namespace breastfit::fit
