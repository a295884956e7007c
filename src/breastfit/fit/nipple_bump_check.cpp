#include "breastfit/fit/nipple_bump_check.h"

namespace breastfit::fit {

NippleBumpCheck check_nipple_bump(const Vec3& given, const NippleBump& bump, double landmark_check_mm) {
  return {(given - bump.position).norm(), kNippleBumpCheckMm * landmark_check_mm / 15.0};
}

}  // namespace breastfit::fit
