#pragma once
/// \file The whole registration of one scan in memory: prepare the scan and landmarks, build the
/// index, fit, and evaluate the fitted template's landmarks and drawings and the paper's errors.
/// What `breastfit register`, `bench` and `demo` run.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/registration.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/metrics/fit_errors.h"
#include "breastfit/metrics/plausibility.h"
#include "breastfit/metrics/surface_coverage.h"
#include "breastfit/model/rigged_model.h"
#include "breastfit/pipeline/provenance.h"
#include "breastfit/pipeline/scan_input.h"
#include "breastfit/transfer/breast_measurements.h"
#include "breastfit/transfer/drawing_transfer.h"
#include "breastfit/transfer/volume_cache.h"

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
  /// A previous fit's parameters to start from (a re-fit after a landmark moved): only the last
  /// stage runs (fit::refit_template). nullopt: the full registration.
  std::optional<model::PoseParams> warm_start;
  /// With warm_start: that fit's final correspondences (fit::FitResult::final_correspondences, a
  /// fit of the same prepared scan with the same options): the re-fit's first ones, not searched
  /// again (the same result). null: searched.
  std::shared_ptr<const fit::Problem::CorrespondenceState> warm_correspondences;
};

struct RegisterResult {
  std::string scan_name;                ///< RegisterRequest::scan_name (the scan file, for reports)
  PreparedScan scan;                    ///< the scan in mm (and its units)
  fit::FitResult fit;                   ///< parameters, posed vertices (mm), solver summary
  /// The landmarks the fit's initialisation placed the template by (as selected, before any
  /// _R/_L correction); fewer than 3: a landmark-free initialisation. The report's figures are
  /// set up from that placement (report_layers.h).
  std::vector<fit::LandmarkTarget> initial_landmarks;
  TriangleMesh fitted_mm;               ///< the posed template, mm, scanner frame
  Markups model_landmarks_mm;           ///< the template's landmarks on the fitted model
  Markups drawings_mm;                  ///< the template's drawings transferred onto the scan (mm)
  std::vector<transfer::TransferredCurve> drawings_on_scan;  ///< the same with support flags and statistics
  transfer::BreastMeasurements breasts; ///< volumes, distances, symmetry
  metrics::SurfaceCoverage coverage;    ///< per fitted vertex: distance to the scan, covered by it or not
  metrics::DistanceStats surface;       ///< paper's surface error (covered fitted vertices → scan)
  metrics::DistanceStats surface_model_only;  ///< the same for the posed template without surface detail
  metrics::LandmarkErrors landmarks;    ///< model landmarks vs input landmarks
  /// A usable fit's shape judged (scale, parameters at bounds, coverage, surface error); its
  /// problems are also in `warnings`. Not judged (plausible) when the fit is not usable.
  metrics::Plausibility plausibility;
  std::vector<std::string> warnings;    ///< everything the user should know
  double time_s = 0;                    ///< scan + landmarks in memory → fitted parameters (index build included)
  /// Wall time per phase: scan_preparation, index_build, the fit's (initialization, stage:<name>,
  /// final_state, surface_detail), transfer, measurements, then measurements:breast_volumes (the
  /// breast volumes' own time: part of measurements, or, with a second thread, measured beside
  /// the transfer and the distances).
  std::vector<fit::PhaseTime> timings;
  std::optional<Provenance> provenance;  ///< RegisterRequest::provenance with the effective options
  /// false: a warm re-fit's first result (register_prepared's `on_surface`): the fitted model, its
  /// landmarks and their errors, the drawings, without the landmark checks and their warnings, the
  /// distances to the scan (coverage, surface errors), the breast measurements and the plausibility.
  bool complete = true;

  bool usable() const { return fit.summary.usable(); }
  /// "ok", "implausible" (usable, but see `plausibility`) or "not_usable" (report.json "status").
  std::string status() const { return !usable() ? "not_usable" : plausibility.plausible ? "ok" : "implausible"; }
};

/// The landmarks a fit's initialisation places the template by, of `targets` (fit::match_landmarks),
/// as fit::register_template selects them (fit::select_landmarks); fewer
/// than 3: a landmark-free initialisation.
std::vector<fit::LandmarkTarget> initialization_landmarks(std::vector<fit::LandmarkTarget> targets,
                                                          const fit::FitOptions& options);

/// Runs the registration. `on_iteration` sees every solver iteration and may abort (the result is
/// then not usable, fit.summary.termination Aborted). \throws InvalidInput for bad scans,
/// landmarks or options; IoError when the default template cannot be read.
RegisterResult register_scan(const RegisterRequest& request, const fit::IterationCallback& on_iteration = {});

/// A scan prepared once for several registrations (the workstation: one scan, many fits): the
/// scan in mm and its closest-point index, and what the fits' breast volumes reuse.
struct PreparedTarget {
  std::string scan_name;
  PreparedScan scan;
  std::unique_ptr<fit::ScanTarget> target;
  std::vector<fit::PhaseTime> timings;  ///< scan_preparation, index_build
  /// The breast volumes' topologies and fill factorisations of the fits so far (the same result
  /// as without it: transfer/volume_cache.h).
  std::shared_ptr<transfer::VolumeCache> volumes = std::make_shared<transfer::VolumeCache>();
  /// One registration only (`register`): register_prepared moves `scan` into its result instead
  /// of copying it, and the target's `scan` is empty afterwards (its index keeps its own mesh).
  bool single_use = false;
};

/// Prepares `scan` (file units) and builds its index with `options`' reverse-term samples;
/// `before_index` sees the prepared scan before the index is built (`register` starts the
/// report's layers there: report_layers.h). \throws InvalidInput as register_scan for a bad scan.
PreparedTarget prepare_target(const TriangleMesh& scan, const std::string& scan_name,
                              std::optional<mesh::Units> units, const fit::FitOptions& options = {},
                              const std::function<void(const PreparedScan&)>& before_index = {});
/// The same, taking over `scan`'s arrays instead of copying them (the scan as read is not needed
/// after its preparation).
PreparedTarget prepare_target(TriangleMesh&& scan, const std::string& scan_name, std::optional<mesh::Units> units,
                              const fit::FitOptions& options = {},
                              const std::function<void(const PreparedScan&)>& before_index = {});

/// Sees a warm re-fit's first result (RegisterResult::complete false; its `scan` empty), on the
/// fitting thread, before the rest is computed.
using SurfaceCallback = std::function<void(const RegisterResult&)>;

/// register_scan on a prepared scan: `request.scan` and `request.units` are not used (the
/// target's are). The target's normal sign is set by the fit: one fit per target at a time.
/// result.time_s is the fit's own time (the index was built before); timings start with the
/// target's. A warm re-fit (request.warm_start) runs in two parts: the fitted model and the
/// drawings first (`on_surface` sees them), then the landmark checks (fit::check_refit), the
/// distances and the breast measurements; the result is the same with or without `on_surface`.
/// \throws as register_scan.
RegisterResult register_prepared(const RegisterRequest& request, PreparedTarget& target,
                                 const fit::IterationCallback& on_iteration = {},
                                 const SurfaceCallback& on_surface = {});

}  // namespace breastfit::pipeline
