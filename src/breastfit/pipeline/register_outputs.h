#pragma once
/// \file Writing the outputs of `breastfit register` in the scan's frame and units:
/// fitted.ply, landmarks.mrk.json, drawings.mrk.json, drawings.ply/.obj, scan_painted.ply,
/// params.json, report.json and report.html (report_html.h).
#include <array>
#include <filesystem>
#include <memory>
#include <vector>

#include "breastfit/model/rigged_model.h"
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/pipeline/report_figures.h"

namespace breastfit::pipeline {

/// The Fiducial markup name and 3D Slicer display colour (cyan) of the fitted landmarks in
/// landmarks.mrk.json, distinct from the input landmarks a person placed (Slicer's default name
/// and colours).
inline constexpr const char* kFittedLandmarksName = "breastfit fitted landmarks";
inline constexpr std::array<double, 3> kFittedLandmarksColor{0.0, 0.75, 1.0};

/// The names of the files write_register_outputs writes (report.json, the completion marker, among them).
std::vector<std::string> register_output_names();

/// Optional parts of the outputs.
struct RegisterOutputOptions {
  bool report_html = true;       ///< write report.html (renders its three images; see report_html.h)
  ReportFigureOptions figures;   ///< the report's images
  /// The report's overlay figures' scan layers, drawn while the fit ran (start_report_layers with
  /// `figures`); nullptr: drawn here (the same bytes).
  std::shared_ptr<ReportLayerDrawing> layers;
};

/// Creates `dir` if needed and writes the outputs as one set (io/output_set.h): all files are
/// written next to `dir` first and moved in together, report.json last; an output of the
/// previous run that this run does not write (report.html without options.report_html) is
/// removed. Other files in `dir` are never touched. report.html is made on a second thread while
/// the other files are written (the same bytes as made alone).
/// \param force      replace existing output files (otherwise an existing one is an error)
/// \param protected_paths  files that must never be overwritten (the inputs), even with force
/// \throws IoError when a file exists without `force`, would overwrite an input, or cannot be written
void write_register_outputs(const std::filesystem::path& dir, const RegisterResult& result,
                            const model::RiggedModel& model, bool force,
                            const std::vector<std::filesystem::path>& protected_paths,
                            const RegisterOutputOptions& options = {});

/// The outputs of a registration that is not usable: `dir` ends up with report.json (status
/// "not_usable") as its only output — the previous run's fitted files are removed, so nothing in
/// `dir` can be mistaken for a result. Same arguments and errors as write_register_outputs.
void write_register_failure(const std::filesystem::path& dir, const RegisterResult& result, bool force,
                            const std::vector<std::filesystem::path>& protected_paths);

/// Checks the output directory before any work: same rules as write_register_outputs.
void check_output_dir(const std::filesystem::path& dir, bool force,
                      const std::vector<std::filesystem::path>& protected_paths);

}  // namespace breastfit::pipeline
