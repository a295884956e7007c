#include "breastfit/fit/combined_check.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace breastfit::fit {

std::optional<double> combined_check_threshold(const std::string& name) {
  // combined_check.h: about 1.1–1.6× the largest r_p² + r_a² of the landmarks as given.
  static const std::vector<std::pair<std::string, double>> table = {
      {"sternal_notch", 0.90},        {"acromion_R", 0.80},           {"acromion_L", 0.80},
      {"midaxillary_R", 1.00},        {"midaxillary_L", 1.00},        {"pectoral_insertion_R", 1.00},
      {"pectoral_insertion_L", 1.00}, {"nipple_R", 0.85},             {"nipple_L", 0.85},
      {"lowest_breast_R", 0.95},      {"lowest_breast_L", 0.95}};
  for (const auto& [n, t] : table)
    if (n == name) return t;
  return std::nullopt;
}

std::optional<double> combined_anatomy_tolerance_mm(const std::string& name, double predicted_ratio,
                                                    double anatomy_tolerance_mm) {
  const auto threshold = combined_check_threshold(name);
  if (!threshold) return std::nullopt;
  return anatomy_tolerance_mm * std::sqrt(std::max(*threshold - predicted_ratio * predicted_ratio, 0.0));
}

}  // namespace breastfit::fit
