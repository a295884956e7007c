#include "breastfit/serve/scan_session.h"

#include <time.h>

#include <cmath>

#include "breastfit/core/errors.h"
#include "breastfit/core/timer.h"
#include "breastfit/io/io.h"

namespace breastfit::serve {

namespace {

double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

}  // namespace

const char* to_string(FitState s) {
  switch (s) {
    case FitState::Idle: return "idle";
    case FitState::Running: return "running";
    case FitState::Done: return "done";
    case FitState::Failed: return "failed";
    case FitState::Cancelled: return "cancelled";
  }
  return "?";
}

ScanSession::ScanSession(std::string id, std::filesystem::path scan_path, std::string display_name,
                         std::shared_ptr<const model::RiggedModel> model, fit::FitOptions options)
    : id_(std::move(id)),
      name_(std::move(display_name)),
      scan_path_(std::move(scan_path)),
      model_(std::move(model)),
      options_(std::move(options)),
      target_(pipeline::prepare_target(io::read_mesh(scan_path_), name_, std::nullopt, options_)),
      frame_(mesh::body_frame_from_principal_axes(target_.scan.mesh_mm)) {}

ScanSession::~ScanSession() {
  cancel();
  wait();
}

std::shared_ptr<const FitOutcome> ScanSession::run_fit(const LandmarkSet& landmarks_mm, bool warm) {
  Timer timer;
  const double cpu_start = thread_cpu_ms();
  pipeline::RegisterRequest req;
  req.scan_name = name_;
  req.landmarks = landmarks_mm;
  req.landmarks->declared_units = "mm";
  req.landmarks_name = "the placed landmarks";
  req.model = model_;
  req.options = options_;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (warm && last_params_) req.warm_start = last_params_;
  }
  auto out = std::make_shared<FitOutcome>();
  out->warm = req.warm_start.has_value();
  const auto on_iteration = [this](const fit::IterationRecord& rec) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      status_.stage = rec.stage;
      ++status_.iterations;
    }
    return cancel_ ? fit::CallbackResult::Abort : fit::CallbackResult::Continue;
  };
  {
    std::lock_guard<std::mutex> use(target_mutex_);
    out->result = pipeline::register_prepared(req, target_, on_iteration);
    const fit::ScanTarget& scan = *target_.target;
    out->distances_mm.reserve(out->result.fit.vertices.rows());
    for (Eigen::Index i = 0; i < out->result.fit.vertices.rows(); ++i)
      out->distances_mm.push_back(std::sqrt(scan.closest(out->result.fit.vertices.row(i).transpose()).sq_dist));
  }
  out->server_ms = 1000 * timer.seconds();
  out->server_cpu_ms = thread_cpu_ms() - cpu_start;
  std::lock_guard<std::mutex> lock(mutex_);
  out->generation = ++generation_;
  if (out->result.usable()) last_params_ = out->result.fit.params;
  return out;
}

bool ScanSession::start_fit(LandmarkSet landmarks_mm, bool warm) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (status_.state == FitState::Running) return false;
  if (worker_.joinable()) worker_.join();  // the previous, finished worker
  cancel_ = false;
  status_.state = FitState::Running;
  status_.stage.clear();
  status_.iterations = 0;
  status_.message.clear();
  worker_ = std::thread([this, landmarks = std::move(landmarks_mm), warm] {
    try {
      auto outcome = run_fit(landmarks, warm);
      if (cancel_ || outcome->result.fit.summary.termination == fit::Termination::Aborted)
        finish(FitState::Cancelled, "cancelled: the fit was stopped; the previous result is kept", nullptr);
      else
        finish(FitState::Done, outcome->result.fit.summary.message, outcome);
    } catch (const std::exception& e) {
      finish(FitState::Failed, e.what(), nullptr);
    }
  });
  return true;
}

void ScanSession::finish(FitState state, std::string message, std::shared_ptr<const FitOutcome> outcome) {
  std::lock_guard<std::mutex> lock(mutex_);
  status_.state = state;
  status_.message = std::move(message);
  if (outcome) status_.outcome = std::move(outcome);
}

bool ScanSession::with_target(const std::function<void(const fit::ScanTarget&)>& f) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (status_.state == FitState::Running) return false;
  }
  std::unique_lock<std::mutex> use(target_mutex_, std::try_to_lock);
  if (!use.owns_lock()) return false;  // a fit has just started
  f(*target_.target);
  return true;
}

void ScanSession::cancel() { cancel_ = true; }

void ScanSession::wait() {
  std::thread t;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    t = std::move(worker_);
  }
  if (t.joinable()) t.join();
}

FitStatus ScanSession::status() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

}  // namespace breastfit::serve
