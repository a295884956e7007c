#pragma once
/// \file One scan open in the workstation: read and indexed once, then fitted as often as the
/// user asks, or its landmarks suggested (pipeline::detect_landmarks) — one job at a time (a
/// second request is refused, not queued), on a worker thread, with its progress readable at any
/// time (or waited for: the page's event stream) and a cancel that ends it after the current
/// iteration.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "breastfit/fit/fit_options.h"
#include "breastfit/io/obj_texture.h"
#include "breastfit/mesh/body_frame.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/model/rigged_model.h"
#include "breastfit/pipeline/detect_landmarks.h"
#include "breastfit/pipeline/register_scan.h"

namespace breastfit::serve {

/// A finished fit as the page sees it.
struct FitOutcome {
  pipeline::RegisterResult result;
  /// per fitted vertex: distance to the scan; NaN where the scan does not cover the model
  /// (metrics/surface_coverage.h), as the report's distance figure
  std::vector<double> distances_mm;
  double server_ms = 0;              ///< the fit request's wall time in the server (fit, transfer, measurements)
  /// The same work's CPU time on its (single) thread: what server_ms is on an idle machine, and
  /// independent of other processes' load.
  double server_cpu_ms = 0;
  /// When the fitted model and its drawings were ready: a warm re-fit sends them before its
  /// landmark checks, distances and breast measurements (ScanSession::start_fit); the same as
  /// server_ms / server_cpu_ms for a fit from scratch.
  double surface_ms = 0;
  double surface_cpu_ms = 0;         ///< the same work's CPU time on the request's thread
  bool warm = false;                 ///< warm-started from the previous fit
  /// false: a warm re-fit's first result (pipeline::RegisterResult::complete), shown while the
  /// job still runs; the job's end brings the complete one.
  bool complete = true;
  int generation = 0;                ///< 1 for the session's first fit, then 2, 3, ...
};

/// Landmarks suggested on the scan (pipeline::detect_landmarks on the open scan), for the user to
/// check and correct before a fit.
struct SuggestOutcome {
  std::vector<pipeline::DetectedLandmark> landmarks;  ///< the template's, in its order
  std::vector<std::string> warnings;                  ///< the landmark-free fit's
  double server_ms = 0;                               ///< wall time in the server
  double server_cpu_ms = 0;                           ///< CPU time of the same work (its one thread)
};

enum class FitState { Idle, Running, Done, Failed, Cancelled };
const char* to_string(FitState s);

/// What the page watches: the running or last job (a fit or a landmark suggestion).
struct FitStatus {
  FitState state = FitState::Idle;
  std::string job = "fit";      ///< the running or last job: "fit" or "suggest"
  std::string stage;            ///< the running stage
  int iterations = 0;           ///< iterations so far (all stages)
  std::string message;          ///< the failure's or cancellation's reason, or the verdict
  std::shared_ptr<const FitOutcome> outcome;  ///< the last finished fit (may be older than state)
  /// The running or last fit's first result when it is a warm re-fit (FitOutcome::complete false:
  /// the fitted model and drawings, before the landmark checks, distances and measurements); null
  /// before it is ready and for a fit from scratch.
  std::shared_ptr<const FitOutcome> first;
  std::shared_ptr<const SuggestOutcome> suggestion;  ///< the last finished suggestion
  uint64_t version = 0;         ///< grows with every change of the above
};

class ScanSession {
 public:
  /// Reads the scan and builds its index (the slow part, done once).
  /// \throws InvalidInput / IoError naming the file for a bad scan
  ScanSession(std::string id, std::filesystem::path scan_path, std::string display_name,
              std::shared_ptr<const model::RiggedModel> model, fit::FitOptions options = {});
  /// Cancels a running fit and waits for it.
  ~ScanSession();
  ScanSession(const ScanSession&) = delete;
  ScanSession& operator=(const ScanSession&) = delete;

  const std::string& id() const { return id_; }
  const std::string& name() const { return name_; }
  const std::filesystem::path& scan_path() const { return scan_path_; }
  const pipeline::PreparedScan& scan() const { return target_.scan; }
  const model::RiggedModel& model() const { return *model_; }
  /// The scan's body frame from its shape (mesh::body_frame_from_principal_axes): the page's
  /// standard views before a fit.
  const mesh::BodyFrame& body_frame() const { return frame_; }
  /// A textured OBJ's colour image (io::obj_texture), for display only: image empty when the
  /// scan is not an OBJ, has no texture coordinates (then problem says so when it names an
  /// image) or names no image.
  const io::ObjTexture& texture() const { return texture_; }
  /// Runs `f` on the scan's closest-point index while no fit of this scan runs (a fit changes the
  /// index's normal sign; one started meanwhile waits for `f`). Returns false, without calling
  /// `f`, when a fit is running.
  bool with_target(const std::function<void(const fit::ScanTarget&)>& f);

  /// Starts a fit with `landmarks_mm` (positions in mm, scan frame). `warm`: start from the last
  /// usable fit's parameters (pipeline::RegisterRequest::warm_start) when there is one.
  /// Returns false (and starts nothing) while another job (fit or suggestion) of this scan runs.
  bool start_fit(LandmarkSet landmarks_mm, bool warm);
  /// Runs a fit on the calling thread (what start_fit's worker runs; benchmarks call it).
  /// `on_surface` sees a warm re-fit's first result (FitOutcome::complete false) before the rest
  /// is computed. \throws InvalidInput for bad landmarks
  std::shared_ptr<const FitOutcome> run_fit(
      const LandmarkSet& landmarks_mm, bool warm,
      const std::function<void(std::shared_ptr<const FitOutcome>)>& on_surface = {});
  /// Starts suggesting the landmarks (a landmark-free fit, then the template's landmarks snapped
  /// to the scan, each with a confidence). Returns false (and starts nothing) while another job
  /// of this scan runs.
  bool start_suggest();
  /// Suggests the landmarks on the calling thread (what start_suggest's worker runs).
  /// \throws InvalidInput when the landmark-free fit is not usable (or was cancelled)
  std::shared_ptr<const SuggestOutcome> run_suggest();
  /// Asks a running job to stop after its current iteration.
  void cancel();
  /// Waits for a running job to end.
  void wait();
  FitStatus status() const;
  /// The status once its version differs from `seen` (at once when it already does), or after
  /// `timeout` whatever it is.
  FitStatus wait_status(uint64_t seen, std::chrono::milliseconds timeout) const;

 private:
  // What a finished job leaves: its message and outcome (one of the two, or none).
  struct JobEnd {
    std::string message;
    std::shared_ptr<const FitOutcome> fit;
    std::shared_ptr<const SuggestOutcome> suggestion;
  };
  bool start_job(std::string job, std::function<JobEnd()> work);
  void finish(FitState state, JobEnd end);
  void show_first(std::shared_ptr<const FitOutcome> first);  // a re-fit's first result while it runs
  fit::IterationCallback progress();  // counts iterations and answers a cancel

  std::string id_, name_;
  std::filesystem::path scan_path_;
  std::shared_ptr<const model::RiggedModel> model_;
  fit::FitOptions options_;
  pipeline::PreparedTarget target_;
  mesh::BodyFrame frame_;
  io::ObjTexture texture_;

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;  // status_.version grew
  std::mutex target_mutex_;  // held while the index is used (a fit, with_target)
  FitStatus status_;
  std::optional<model::PoseParams> last_params_;  // of the last usable fit
  std::shared_ptr<const fit::Problem::CorrespondenceState> last_correspondences_;  // its final ones
  int generation_ = 0;
  std::atomic<bool> cancel_{false};
  std::thread worker_;
};

}  // namespace breastfit::serve
