#pragma once
/// \file Writing the outputs of `breastfit register` in the scan's frame and units:
/// fitted.ply, landmarks.mrk.json, drawings.mrk.json, params.json, report.json.
#include <filesystem>
#include <vector>

#include "breastfit/model/rigged_model.h"
#include "breastfit/pipeline/register_scan.h"

namespace breastfit::pipeline {

/// The names of the files write_register_outputs writes.
std::vector<std::string> register_output_names();

/// Creates `dir` if needed and writes the outputs.
/// \param force      replace existing output files (otherwise an existing one is an error)
/// \param protected_paths  files that must never be overwritten (the inputs), even with force
/// \throws IoError when a file exists without `force`, would overwrite an input, or cannot be written
void write_register_outputs(const std::filesystem::path& dir, const RegisterResult& result,
                            const model::RiggedModel& model, bool force,
                            const std::vector<std::filesystem::path>& protected_paths);

/// Checks the output directory before any work: same rules as write_register_outputs.
void check_output_dir(const std::filesystem::path& dir, bool force,
                      const std::vector<std::filesystem::path>& protected_paths);

}  // namespace breastfit::pipeline
