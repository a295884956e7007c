#include "breastfit/fit/landmark_target.h"

namespace breastfit::fit {

double landmark_weight(const std::string& name) {
  if (name.rfind("midaxillary", 0) == 0) return 0.1;
  return 1.0;
}

}  // namespace breastfit::fit
