#pragma once
/// \file One term of the registration energy, behind one interface (in the spirit of Ceres'
/// `CostFunction`): a term evaluates its weighted squared residuals at the evaluator's current
/// parameters and, when asked, adds their Gauss–Newton rows to the normal equations.
///
/// E(θ) = Σ_terms  (1/λ_term) · cost_term(θ),   cost_term = Σ_rows w_row r_row(θ)²
///
/// A term is described by a TermSpec (name, λ default, units, help) in the table of
/// energy_terms.h; the options (EnergyWeights), the command-line flags (`--lambda-NAME`), the JSON
/// keys (`weights.lambda_NAME`) and the energies in report.json are all derived from that table.
/// Adding a term = one new .cpp file (a class deriving from EnergyTerm, and its spec) and its line
/// in energy_terms.cpp (docs/ARCHITECTURE.md, "Where to add … an energy term").
#include <memory>
#include <string_view>
#include <vector>

#include "breastfit/fit/correspondences.h"
#include "breastfit/fit/landmark_target.h"
#include "breastfit/fit/normal_equations.h"
#include "breastfit/model/pose_evaluator.h"

namespace breastfit::fit {

struct FitOptions;

/// What a term may read: the posed model and the targets held fixed during one outer iteration.
struct TermContext {
  const model::PoseEvaluator& ev;                     ///< the model at the current parameters
  const std::vector<Correspondence>& pairs;           ///< model vertex → scan (data term)
  const std::vector<ReverseCorrespondence>& reverse;  ///< scan sample → model (reverse term)
  const std::vector<LandmarkTarget>& landmarks;       ///< input landmarks matched to the model
  const FitOptions& options;
  bool robust_landmarks = false;  ///< this stage down-weights landmarks beyond their check tolerance (landmark_check.h)
};

class EnergyTerm {
 public:
  virtual ~EnergyTerm() = default;
  /// Once per outer iteration, before evaluate, at the iteration's parameters: re-chooses what the
  /// term holds fixed while the step is solved (e.g. the model point of a sliding landmark).
  virtual void update(const TermContext& ctx) {}
  /// `weight` · Σ w r² at ctx.ev's current parameters (weight = 1/λ); with `eq`, also adds the
  /// rows weight·w·(r + J δ)² to the normal equations. Returns the weighted cost.
  virtual double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const = 0;
};

/// A term's entry in the table of energy_terms.h.
struct TermSpec {
  std::string_view name;     ///< energy key; λ option `weights.lambda_<name>`, flag `--lambda-<name>`
  std::string_view symbol;   ///< the paper's symbol, e.g. "λD"
  double default_lambda;     ///< λ by default (smaller λ = stronger term)
  std::string_view units;    ///< units of λ, e.g. "mm²"
  std::string_view help;     ///< one line for --help and the docs
  bool can_disable = false;  ///< λ ≤ 0 switches the term off (otherwise λ must be > 0)
  std::unique_ptr<EnergyTerm> (*make)() = nullptr;
};

}  // namespace breastfit::fit
