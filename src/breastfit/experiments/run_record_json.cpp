#include "breastfit/experiments/run_record_json.h"

#include <cmath>

namespace breastfit::experiments {
namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json stats(const metrics::DistanceStats& s) {
  return {{"n", s.n}, {"mae", number(s.mae)}, {"sd", number(s.sd)}, {"max", number(s.max)},
          {"min", number(s.min)}, {"rmse", number(s.rmse)}};
}

}  // namespace

nlohmann::json to_json(const RunRecord& r) {
  nlohmann::json j = {{"case", r.case_id},
                      {"pose", r.pose},
                      {"status", r.status},
                      {"message", r.message},
                      {"time_s", number(r.time_s)},
                      {"iterations", r.iterations},
                      {"initialization", r.initialization},
                      {"landmarks_used", r.landmarks_used},
                      {"template_vertices", r.template_vertices}};
  if (!r.has_numbers()) return j;
  j["paper"] = {{"surface", stats(r.paper_surface)}, {"landmarks", stats(r.paper_landmarks)}};
  if (r.has_truth) {
    nlohmann::json d = nlohmann::json::object();
    for (const auto& [name, v] : r.drawings_mm) d[name] = number(v);
    j["truth"] = {{"surface", stats(r.truth_surface)}, {"landmarks", stats(r.truth_landmarks)}, {"drawings_mm", d}};
  }
  return j;
}

}  // namespace breastfit::experiments
