#include "breastfit/fit/landmark_target.h"

namespace breastfit::fit {

double landmark_weight(const std::string& name) {
  if (name.rfind("midaxillary", 0) == 0) return 0.1;
  return 1.0;
}

const LandmarkTarget* find_landmark(const std::vector<LandmarkTarget>& targets, const std::string& name) {
  for (const auto& t : targets)
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace breastfit::fit
