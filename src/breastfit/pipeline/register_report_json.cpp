#include "breastfit/pipeline/register_report_json.h"

#include <string>

#include "breastfit/fit/fit_summary_json.h"
#include "breastfit/mesh/units.h"
#include "breastfit/metrics/distance_stats_json.h"
#include "breastfit/pipeline/provenance_json.h"
#include "breastfit/transfer/breast_measurements_json.h"

namespace breastfit::pipeline {

nlohmann::json report_json(const RegisterResult& r) {
  const auto& s = r.fit.summary;
  nlohmann::json per_landmark = nlohmann::json::object();
  for (size_t i = 0; i < r.landmarks.names.size(); ++i) per_landmark[r.landmarks.names[i]] = r.landmarks.distances_mm[i];
  nlohmann::json j;
  j["time_s"] = r.time_s;
  j["status"] = r.usable() ? "ok" : "not_usable";
  j["units"] = std::string(mesh::units_name(r.scan.units));
  j["point_cloud"] = r.scan.was_point_cloud;
  j["iterations"] = s.iterations.size();
  j["stopping_reason"] = s.termination_message;
  j["termination"] = fit::to_string(s.termination);
  j["converged"] = s.converged();
  j["verdict"] = s.verdict.reason;
  j["timings_s"] = fit::timings_json(r.timings);
  j["solver"] = fit::to_json(s);
  j["table1"] = {{"surface_mm", metrics::to_json(r.surface)},
                 {"surface_model_only_mm", metrics::to_json(r.surface_model_only)},
                 {"landmarks_mm", metrics::to_json(r.landmarks.stats)},
                 {"landmark_errors_mm", per_landmark}};
  nlohmann::json curves = nlohmann::json::object();
  for (const auto& c : r.drawings_on_scan)
    curves[c.name] = {{"closed", c.closed}, {"points", c.points.rows()}, {"length_mm", c.length_mm},
                      {"supported_fraction", c.supported_fraction}, {"mean_model_to_scan_mm", c.mean_model_to_scan_mm}};
  j["drawings"] = curves;
  j["breast_measurements"] = transfer::to_json(r.breasts);
  j["warnings"] = r.warnings;
  if (r.provenance) {
    j["provenance"] = provenance_json(*r.provenance);
    j["run"] = run_json(*r.provenance);
  }
  return j;
}

}  // namespace breastfit::pipeline
