#include "breastfit/transfer/surface_map_json.h"

#include <algorithm>

namespace breastfit::transfer {

nlohmann::json to_json(const MapResult& r) {
  nlohmann::json pts = nlohmann::json::array();
  double max_d = 0, sum_d = 0;
  int supported = 0, projected = 0;
  for (const auto& p : r.points) {
    pts.push_back({{"markup", p.markup},
                   {"label", p.label},
                   {"input_mm", {p.input.x(), p.input.y(), p.input.z()}},
                   {"output_mm", {p.output.x(), p.output.y(), p.output.z()}},
                   {"distance_to_fit_a_mm", p.distance_to_fit_a_mm},
                   {"projected_on_scan_b", p.projected},
                   {"supported_by_scan_b", p.supported_by_scan_b},
                   {"scan_b_offset_mm", p.scan_b_offset_mm},
                   {"confidence", p.confidence}});
    max_d = std::max(max_d, p.distance_to_fit_a_mm);
    sum_d += p.distance_to_fit_a_mm;
    supported += p.supported_by_scan_b;
    projected += p.projected;
  }
  const nlohmann::json summary = {
      {"points", r.points.size()},
      {"high", r.count("high")},
      {"medium", r.count("medium")},
      {"low", r.count("low")},
      {"mean_distance_to_fit_a_mm", r.points.empty() ? 0.0 : sum_d / static_cast<double>(r.points.size())},
      {"max_distance_to_fit_a_mm", max_d},
      {"supported_by_scan_b", supported},
      {"projected_on_scan_b", projected}};
  return {{"format", "breastfit.map"}, {"version", 1}, {"units", "mm"}, {"summary", summary}, {"points", pts}};
}

}  // namespace breastfit::transfer
