#include "breastfit/serve/scan_session.h"

#include <time.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

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
      frame_(mesh::body_frame_from_principal_axes(target_.scan.mesh_mm)) {
  std::string ext = scan_path_.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".obj") return;
  texture_ = io::obj_texture(scan_path_);
  if (!texture_.image.empty() && !target_.scan.mesh_mm.has_texcoords()) {
    texture_.problem = "it names the image " + texture_.image.filename().string() +
                       " but not every face has texture coordinates (vt)";
    texture_.image.clear();
  }
}

ScanSession::~ScanSession() {
  cancel();
  wait();
}

namespace {

// Per fitted vertex: the distance to the scan; NaN where the scan does not cover the model, as
// the report's distance figure (a fit that is not usable has no coverage: every distance).
std::vector<double> vertex_distances(const pipeline::RegisterResult& r, const fit::ScanTarget& scan) {
  const auto n = static_cast<size_t>(r.fit.vertices.rows());
  const metrics::SurfaceCoverage& cov = r.coverage;
  std::vector<double> out;
  out.reserve(n);
  if (cov.distance_mm.size() == n && cov.covered.size() == n) {
    for (size_t i = 0; i < n; ++i)
      out.push_back(cov.covered[i] ? cov.distance_mm[i] : std::numeric_limits<double>::quiet_NaN());
  } else {
    for (Eigen::Index i = 0; i < r.fit.vertices.rows(); ++i)
      out.push_back(std::sqrt(scan.closest(r.fit.vertices.row(i).transpose()).sq_dist));
  }
  return out;
}

}  // namespace

std::shared_ptr<const FitOutcome> ScanSession::run_fit(
    const LandmarkSet& landmarks_mm, bool warm, const std::function<void(std::shared_ptr<const FitOutcome>)>& on_surface) {
  Timer timer;
  const double cpu_start = thread_cpu_ms();
  pipeline::RegisterRequest req;
  req.scan_name = name_;
  req.landmarks = landmarks_mm;
  req.landmarks->declared_units = "mm";
  req.landmarks_name = "the placed landmarks";
  req.model = model_;
  req.options = options_;
  int generation = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (warm && last_params_) {
      req.warm_start = last_params_;
      req.warm_correspondences = last_correspondences_;
    }
    generation = generation_ + 1;
  }
  auto out = std::make_shared<FitOutcome>();
  out->warm = req.warm_start.has_value();
  {
    std::lock_guard<std::mutex> use(target_mutex_);
    const fit::ScanTarget& scan = *target_.target;
    // A re-fit's first result (no distances yet: they follow), made whether shown or not (the
    // bench times what the page gets).
    auto first = [&](const pipeline::RegisterResult& r) {
      auto shown = std::make_shared<FitOutcome>();
      shown->result = r;
      shown->warm = out->warm;
      shown->complete = false;
      shown->generation = generation;
      out->surface_ms = shown->server_ms = shown->surface_ms = 1000 * timer.seconds();
      out->surface_cpu_ms = shown->server_cpu_ms = shown->surface_cpu_ms = thread_cpu_ms() - cpu_start;
      if (on_surface && !cancel_) on_surface(std::move(shown));  // a cancelled re-fit shows nothing
    };
    out->result = pipeline::register_prepared(req, target_, progress(), first);
    out->distances_mm = vertex_distances(out->result, scan);
  }
  out->server_ms = 1000 * timer.seconds();
  out->server_cpu_ms = thread_cpu_ms() - cpu_start;
  if (!out->warm) {
    out->surface_ms = out->server_ms;
    out->surface_cpu_ms = out->server_cpu_ms;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  out->generation = ++generation_;
  if (out->result.usable()) {
    last_params_ = out->result.fit.params;
    last_correspondences_ = out->result.fit.final_correspondences;
  }
  return out;
}

fit::IterationCallback ScanSession::progress() {
  return [this](const fit::IterationRecord& rec) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      status_.stage = rec.stage;
      ++status_.iterations;
      ++status_.version;
    }
    changed_.notify_all();
    return cancel_ ? fit::CallbackResult::Abort : fit::CallbackResult::Continue;
  };
}

std::shared_ptr<const SuggestOutcome> ScanSession::run_suggest() {
  Timer timer;
  const double cpu_start = thread_cpu_ms();
  pipeline::RegisterRequest req;
  req.scan_name = name_;
  req.model = model_;
  req.options = options_;
  auto out = std::make_shared<SuggestOutcome>();
  {
    std::lock_guard<std::mutex> use(target_mutex_);
    pipeline::DetectedLandmarks d = pipeline::detect_landmarks(req, target_, progress());
    out->landmarks = std::move(d.landmarks);
    out->warnings = std::move(d.registration.warnings);
  }
  out->server_ms = 1000 * timer.seconds();
  out->server_cpu_ms = thread_cpu_ms() - cpu_start;
  return out;
}

bool ScanSession::start_fit(LandmarkSet landmarks_mm, bool warm) {
  return start_job("fit", [this, landmarks = std::move(landmarks_mm), warm] {
    auto outcome = run_fit(landmarks, warm, [this](std::shared_ptr<const FitOutcome> first) { show_first(std::move(first)); });
    return JobEnd{outcome->result.fit.summary.message, outcome, nullptr};
  });
}

bool ScanSession::start_suggest() {
  return start_job("suggest", [this] {
    auto outcome = run_suggest();
    return JobEnd{std::to_string(outcome->landmarks.size()) + " landmarks suggested", nullptr, outcome};
  });
}

bool ScanSession::start_job(std::string job, std::function<JobEnd()> work) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (status_.state == FitState::Running) return false;
    if (worker_.joinable()) worker_.join();  // the previous, finished worker
    cancel_ = false;
    status_.state = FitState::Running;
    status_.job = std::move(job);
    status_.stage.clear();
    status_.iterations = 0;
    status_.message.clear();
    status_.first.reset();
    ++status_.version;
    worker_ = std::thread([this, work = std::move(work), fit = status_.job == "fit"] {
      // A cancelled fit ends Aborted, a cancelled suggestion throws: either way cancel_ tells.
      const std::string cancelled = fit ? "cancelled: the fit was stopped; the previous result is kept"
                                                         : "cancelled: no landmarks were suggested";
      try {
        JobEnd end = work();
        if (cancel_)
          finish(FitState::Cancelled, {cancelled, nullptr, nullptr});
        else
          finish(FitState::Done, std::move(end));
      } catch (const std::exception& e) {
        finish(cancel_ ? FitState::Cancelled : FitState::Failed, {cancel_ ? cancelled : e.what(), nullptr, nullptr});
      }
    });
  }
  changed_.notify_all();
  return true;
}

void ScanSession::show_first(std::shared_ptr<const FitOutcome> first) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    status_.first = std::move(first);
    ++status_.version;
  }
  changed_.notify_all();
}

void ScanSession::finish(FitState state, JobEnd end) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    status_.state = state;
    status_.message = std::move(end.message);
    if (end.fit) status_.outcome = std::move(end.fit);
    if (end.suggestion) status_.suggestion = std::move(end.suggestion);
    ++status_.version;
  }
  changed_.notify_all();
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

FitStatus ScanSession::wait_status(uint64_t seen, std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait_for(lock, timeout, [&] { return status_.version != seen; });
  return status_;
}

}  // namespace breastfit::serve
