#pragma once
/// \file What `breastfit experiments` runs: which experiments of the paper (Table 1, Figs 4–8,
/// the resolution remark of §4) and on which grids. The full grids fit the 14 bench cases in
/// under 10 minutes on a 2-core machine; quick() is the reduced set the tests run.
#include <filesystem>
#include <string>
#include <vector>

#include "breastfit/fit/fit_options.h"

namespace breastfit::experiments {

/// Names of the experiments, in the order they run (also the names --skip takes).
inline const std::vector<std::string> kExperimentNames = {"table1", "landmarks", "blendshapes", "lambdas",
                                                          "resolution"};

/// The λ of the sensitivity analysis (Figs 7–8), as fields of fit::EnergyWeights, with the
/// paper's symbols.
struct LambdaSpec {
  std::string field;               ///< "lambda_data", ...
  std::string symbol;              ///< "λD", ...
  std::vector<std::string> terms;  ///< the energy terms it scales (fit/energy_terms.h)
};
const std::vector<LambdaSpec>& sensitivity_lambdas();

/// Value of a λ field ("lambda_<term>") in `weights`. \throws InvalidInput for an unknown field.
double lambda_value(const fit::EnergyWeights& weights, const std::string& field);
/// Multiplies a λ field by `factor`; "lambda_landmarks" (the paper's λL) scales the material and
/// the sliding landmark terms together. \throws InvalidInput for an unknown field.
void scale_lambda(fit::EnergyWeights& weights, const std::string& field, double factor);

struct ExperimentOptions {
  std::vector<std::string> skip;       ///< experiments not run (names of kExperimentNames)
  /// Fig. 4: numbers of landmarks used (the first n in the paper's order, kLandmarkNames).
  std::vector<int> landmark_counts{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  /// Figs 5–6: numbers of blendshapes (the first n of the template); -1 = all.
  std::vector<int> blendshape_counts{0, 5, 10, 15, 20, 25, 30, 35, 40, 45, 50, -1};
  /// Figs 7–8: multipliers of each λ's default, one λ at a time (1 = the defaults, always included).
  std::vector<double> lambda_factors{0.01, 0.1, 1.0 / 3.0, 3.0, 10.0, 100.0};
  /// Resolution: target edge lengths of templates built by templ::build_default_template (the
  /// default template is 16 mm, ~2k vertices; halving the edge gives ~4x the vertices; the
  /// builder accepts 8–40 mm, so ×4 is the finest).
  std::vector<double> resolution_edges_mm{24.0, 16.0, 11.3, 8.0};
  fit::FitOptions fit;                 ///< the default configuration (Table 1)
  std::filesystem::path template_cache_dir;  ///< where built templates are cached (.glb); empty = none
  std::filesystem::path contract_dir;  ///< when set, Table-1 outputs go to contract_dir/<case>/ (referee layout)

  bool runs(const std::string& experiment) const;
  /// The reduced grids for tests and CI: landmarks {0, 3, 12}, blendshapes {0, all}, λ × {1/10, 10},
  /// resolution at the default edge only.
  static ExperimentOptions quick();
  /// \throws InvalidInput for an unknown experiment name in skip, or out-of-range grid values.
  void validate() const;
};

}  // namespace breastfit::experiments
