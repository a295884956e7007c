#pragma once
/// \file The sweeps of run_experiments (Figs 4–8 and the resolution experiment) as Markdown
/// tables of the means over cases, standing and supine: the numbers behind the plots, ready to
/// paste into docs/EXPERIMENTS.md.
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace breastfit::experiments {

/// One section per experiment present in the JSON (landmarks, blendshapes, lambdas, resolution).
std::string sweeps_markdown(const nlohmann::json& experiments);

}  // namespace breastfit::experiments
