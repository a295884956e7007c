#pragma once
/// \file Writing the outputs of `breastfit register` in the scan's frame and units:
/// fitted.ply, landmarks.mrk.json, drawings.mrk.json, drawings.ply/.obj, scan_painted.ply,
/// params.json, report.json and report.html (report_html.h).
#include <filesystem>
#include <vector>

#include "breastfit/model/rigged_model.h"
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/pipeline/report_figures.h"

namespace breastfit::pipeline {

/// The names of the files write_register_outputs writes.
std::vector<std::string> register_output_names();

/// Optional parts of the outputs.
struct RegisterOutputOptions {
  bool report_html = true;       ///< write report.html (renders its three images; see report_html.h)
  ReportFigureOptions figures;   ///< the report's images
};

/// Creates `dir` if needed and writes the outputs. Without report.html (options), an existing
/// report.html in `dir` is removed (it would describe another run; `force` is needed for that).
/// \param force      replace existing output files (otherwise an existing one is an error)
/// \param protected_paths  files that must never be overwritten (the inputs), even with force
/// \throws IoError when a file exists without `force`, would overwrite an input, or cannot be written
void write_register_outputs(const std::filesystem::path& dir, const RegisterResult& result,
                            const model::RiggedModel& model, bool force,
                            const std::vector<std::filesystem::path>& protected_paths,
                            const RegisterOutputOptions& options = {});

/// Checks the output directory before any work: same rules as write_register_outputs.
void check_output_dir(const std::filesystem::path& dir, bool force,
                      const std::vector<std::filesystem::path>& protected_paths);

}  // namespace breastfit::pipeline
