#include "breastfit/fit/hanging_acromion.h"

namespace breastfit::fit {

Vec3 hanging_acromion_target(const Vec3& fitted, const SternumFrame& frame, const HangingAcromionOptions& options) {
  return fitted + options.up_mm * frame.up - options.medial_mm * frame.lateral;
}

}  // namespace breastfit::fit
