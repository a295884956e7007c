#pragma once
/// \file The whole registration of one scan in memory: prepare the scan and landmarks, build the
/// index, fit, and evaluate the fitted template's landmarks and drawings and the paper's errors.
/// What `breastfit register`, `bench` and `demo` run.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/registration.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/metrics/fit_errors.h"
#include "breastfit/model/rigged_model.h"
#include "breastfit/pipeline/provenance.h"
#include "breastfit/pipeline/scan_input.h"
#include "breastfit/transfer/breast_measurements.h"
#include "breastfit/transfer/drawing_transfer.h"

namespace breastfit::pipeline {

/// Everything one registration needs, owned by the request (nothing dangles when it is kept or
/// moved to another thread): the scan and landmarks as read, the template (shared: one loaded
/// template serves many registrations), the options.
struct RegisterRequest {
  TriangleMesh scan;                           ///< as read: file units, scanner frame
  std::string scan_name = "scan";              ///< for messages
  std::optional<mesh::Units> units;            ///< forced units (nullopt: detect)
  std::optional<LandmarkSet> landmarks;        ///< as read (nullopt: none given)
  std::string landmarks_name = "landmarks";    ///< for messages (the landmark file)
  std::shared_ptr<const model::RiggedModel> model;  ///< the template (nullptr: the shipped default)
  fit::FitOptions options;
  /// What the command read and how it ran (report.json's provenance and run blocks); its
  /// options are replaced by `options` (the effective ones). nullopt: no such blocks.
  std::optional<Provenance> provenance;
};

struct RegisterResult {
  std::string scan_name;                ///< RegisterRequest::scan_name (the scan file, for reports)
  PreparedScan scan;                    ///< the scan in mm (and its units)
  fit::FitResult fit;                   ///< parameters, posed vertices (mm), solver summary
  TriangleMesh fitted_mm;               ///< the posed template, mm, scanner frame
  Markups model_landmarks_mm;           ///< the template's landmarks on the fitted model
  Markups drawings_mm;                  ///< the template's drawings transferred onto the scan (mm)
  std::vector<transfer::TransferredCurve> drawings_on_scan;  ///< the same with support flags and statistics
  transfer::BreastMeasurements breasts; ///< volumes, distances, symmetry
  metrics::DistanceStats surface;       ///< paper's surface error (fitted vertices → scan)
  metrics::DistanceStats surface_model_only;  ///< the same for the posed template without surface detail
  metrics::LandmarkErrors landmarks;    ///< model landmarks vs input landmarks
  std::vector<std::string> warnings;    ///< everything the user should know
  double time_s = 0;                    ///< scan + landmarks in memory → fitted parameters (index build included)
  /// Wall time per phase: scan_preparation, index_build, the fit's (initialization, stage:<name>,
  /// final_state, surface_detail), transfer, measurements.
  std::vector<fit::PhaseTime> timings;
  std::optional<Provenance> provenance;  ///< RegisterRequest::provenance with the effective options

  bool usable() const { return fit.summary.usable(); }
};

/// Runs the registration. `on_iteration` sees every solver iteration and may abort (the result is
/// then not usable, fit.summary.termination Aborted). \throws InvalidInput for bad scans,
/// landmarks or options; IoError when the default template cannot be read.
RegisterResult register_scan(const RegisterRequest& request, const fit::IterationCallback& on_iteration = {});

}  // namespace breastfit::pipeline
