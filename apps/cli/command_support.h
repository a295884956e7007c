#pragma once
/// \file Pieces shared by the subcommands that fit: template loading, fit-option flags,
/// progress lines and the printed summary.
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/fit_summary.h"
#include "breastfit/mesh/units.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::pipeline {
struct RegisterResult;
}

namespace breastfit::cli {

/// λ overrides from the command line (unset = keep the config/default value).
struct FitFlags {
  /// One `--lambda-<term>` flag per energy term (fit/energy_terms.h), by term name.
  std::map<std::string, std::optional<double>> lambdas;
  std::optional<int> max_blendshapes, max_landmarks;
  bool no_surface_detail = false;
  std::optional<int> threads;  ///< --threads (FitOptions::threads)
};

void add_fit_flags(CLI::App& sub, FitFlags& flags);
/// Defaults, then the JSON config file (if any), then the flags. \throws IoError / InvalidInput.
fit::FitOptions load_fit_options(const std::string& config_path, const FitFlags& flags);
/// "auto" → nullopt, "mm"/"m" → the units.
std::optional<mesh::Units> parse_units_flag(const std::string& text);
/// Before writing an output file: refuses (IoError naming the file) when it is one of `inputs`,
/// or when it exists and `force` is false. Nothing the user gave is overwritten.
void check_output_file(const std::string& path, const std::vector<std::string>& inputs, bool force,
                       const std::string& force_flag = "--force");
/// The template at `path`, or the shipped default when empty; `mesh` picks one of several skinned
/// meshes (model::load_gltf). \throws IoError / InvalidInput.
model::RiggedModel load_template(const std::string& path, const std::string& mesh = "");
/// One line per iteration on stderr unless quiet.
fit::IterationCallback progress_printer(bool quiet);
/// Remembers the process's command line (main does this first) for the reports' provenance.
void set_command_line(int argc, const char* const* argv);
/// The command line set_command_line remembered (empty before).
const std::vector<std::string>& command_line();
/// The human summary of a registration (`report_html`: report.html was written too).
void print_register_summary(std::ostream& os, const pipeline::RegisterResult& r, const std::string& out_dir,
                            bool report_html = true);

}  // namespace breastfit::cli
