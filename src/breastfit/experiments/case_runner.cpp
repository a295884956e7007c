#include "breastfit/experiments/case_runner.h"

#include <limits>
#include <optional>

#include "breastfit/core/errors.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/metrics/truth_errors.h"
#include "breastfit/pipeline/scan_input.h"
#include "breastfit/spatial/closest_point_index.h"

namespace breastfit::experiments {

/// What every run of the case is compared with, built once.
struct CaseRunner::Reference {
  std::optional<fit::ScanTarget> scan_mm;             ///< for the truth's "observed" test
  std::optional<spatial::ClosestPointIndex> truth;    ///< the truth surface
};

CaseRunner::CaseRunner(const EvalCase& c) : case_(c), ref_(std::make_unique<Reference>()) {
  if (c.truth) {
    const pipeline::PreparedScan p = pipeline::prepare_scan(c.scan, (c.dir / "scan.ply").string(), c.units);
    ref_->scan_mm.emplace(p.mesh_mm, 0);
    ref_->truth.emplace(c.truth->surface_mm);
  }
}

CaseRunner::~CaseRunner() = default;

std::string run_status(const fit::FitSummary& s) {
  if (s.usable()) return "ok";
  return s.converged() ? "not_usable" : "not_converged";
}

RunRecord CaseRunner::score(const pipeline::RegisterResult& r) const {
  RunRecord rec;
  rec.case_id = case_.id;
  rec.pose = case_.pose;
  rec.status = run_status(r.fit.summary);
  rec.message = r.fit.summary.message;
  rec.time_s = r.time_s;
  rec.iterations = static_cast<int>(r.fit.summary.iterations.size());
  rec.initialization = r.fit.summary.initialization;
  rec.landmarks_used = r.fit.summary.landmarks_used;
  rec.template_vertices = static_cast<int>(r.fit.vertices.rows());
  rec.paper_surface = r.surface;

  // Model landmarks against every landmark placed on the scan (not only those used in the fit:
  // the landmark-count experiment measures all 12 whatever the fit used).
  std::vector<double> d;
  for (const auto& [name, pos] : case_.landmarks_mm)
    if (const NamedPoint* m = r.model_landmarks_mm.find_point(name)) d.push_back((m->position - pos).norm());
  rec.paper_landmarks = metrics::distance_stats(d);

  if (case_.truth && ref_->truth && ref_->scan_mm) {
    rec.has_truth = true;
    const auto te = metrics::truth_errors(r.fit.vertices, *ref_->truth, *ref_->scan_mm, r.model_landmarks_mm.points,
                                          case_.truth->landmarks_mm);
    rec.truth_surface = te.surface;
    rec.truth_landmarks = te.landmarks;
    for (const auto& t : case_.truth->curves_mm) {
      const Curve* c = r.drawings_mm.find_curve(t.name);
      rec.drawings_mm.emplace_back(t.name, c && c->points.rows() >= 2 ? metrics::curve_distance(*c, t)
                                                                      : std::numeric_limits<double>::quiet_NaN());
    }
  }
  return rec;
}

RunRecord CaseRunner::run(const model::RiggedModel& model, const fit::FitOptions& options,
                          const std::function<void(const pipeline::RegisterResult&)>& on_result) const {
  pipeline::RegisterRequest req;
  req.scan = case_.scan;
  req.scan_name = (case_.dir / "scan.ply").string();
  req.units = case_.units;
  req.landmarks = case_.landmarks;
  // Not owned: CaseRunner::run's caller keeps `model` alive for the call (aliasing, no deleter).
  req.model = std::shared_ptr<const model::RiggedModel>(std::shared_ptr<const void>(), &model);
  req.options = options;
  std::optional<pipeline::RegisterResult> result;
  try {
    result = pipeline::register_scan(req);
  } catch (const std::exception& e) {  // invalid options or input for this configuration: recorded
    RunRecord rec;
    rec.case_id = case_.id;
    rec.pose = case_.pose;
    rec.status = "error";
    rec.message = e.what();
    rec.template_vertices = static_cast<int>(model.num_vertices());
    return rec;
  }
  RunRecord rec = score(*result);
  if (on_result) on_result(*result);
  return rec;
}

}  // namespace breastfit::experiments
