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
  j["status"] = r.status();
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
  const auto& c = r.coverage;
  j["scan_coverage"] = {{"model_vertices", c.distance_mm.size()},
                        {"covered_vertices", c.covered_count},
                        {"fraction", c.fraction()},
                        {"max_distance_mm", c.options.max_distance_mm},
                        {"max_normal_angle_deg", c.options.max_normal_angle_deg},
                        {"border_excluded", c.options.skip_border}};
  const auto& p = r.plausibility;
  j["plausibility"] = {{"plausible", p.plausible},
                       {"problems", p.problems},
                       {"global_scale", p.global_scale},
                       {"parameters_at_bound", p.at_bound},
                       {"bounded_parameters", p.bounded_parameters}};
  j["breast_measurements"] = transfer::to_json(r.breasts);
  j["warnings"] = r.warnings;
  if (r.provenance) {
    j["provenance"] = provenance_json(*r.provenance);
    j["run"] = run_json(*r.provenance);
  }
  return j;
}

}  // namespace breastfit::pipeline
