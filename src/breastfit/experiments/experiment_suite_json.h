#pragma once
/// \file The paper's experiments (Mazier et al. 2022, §3) on a directory of cases, in process:
/// each case is loaded once and registered once per configuration.
///
///  - table1:      the default configuration: time, surface and landmark errors the paper's way
///                 (model → scan) and against the truth, drawing errors;
///  - landmarks:   Fig. 4, the first n landmarks in the paper's order (kLandmarkNames) for each
///                 n of the grid; landmark errors always over all 12;
///  - blendshapes: Figs 5–6, only the first n blendshapes of the template free;
///  - lambdas:     Figs 7–8, λD, λS, λBS, λJ, λL one at a time × each factor;
///  - resolution:  §4's remark, the default template rebuilt at other edge lengths.
/// Runs that reproduce the default configuration (12 landmarks, all blendshapes, factor 1, the
/// default template's resolution) reuse the table1 run instead of registering again.
///
/// Example:
/// \code
///   auto dirs = experiments::find_case_dirs("cases");
///   nlohmann::json j = experiments::run_experiments(dirs, model, experiments::ExperimentOptions::quick());
/// \endcode
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "breastfit/experiments/experiment_options.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::experiments {

/// Receives one progress line (no newline).
using ProgressFn = std::function<void(const std::string&)>;

/// Runs the experiments `options` selects on the cases, with `model` as the template.
/// \return every number (layout in docs/EXPERIMENTS.md): "config", "cases", and one object per
///         experiment that ran ("table1", "landmarks", "blendshapes", "lambdas", "resolution"),
///         each with "runs" (one record per registration, see run_record_json.h, plus the setting)
///         and "summary" (means per setting, standing / supine / all, see run_summary_json.h),
///         and "wall_time_s".
/// A case that cannot be loaded is listed under "cases" with its error and skipped; a
/// registration that fails is recorded (status "error") and the experiments go on.
/// \throws InvalidInput for invalid options; IoError when the template cache or the contract
///         outputs (options.contract_dir) cannot be written.
nlohmann::json run_experiments(const std::vector<std::filesystem::path>& case_dirs, const model::RiggedModel& model,
                               const ExperimentOptions& options, const ProgressFn& progress = {});

}  // namespace breastfit::experiments
