#pragma once
/// The sternum frame the fit's detector tests build their scans in: the notch at the origin, a
/// 200 mm sternum, up z, front y, lateral x.
#include "breastfit/fit/shoulder_landmarks.h"

namespace breastfit::fit::test {

inline SternumFrame unit_sternum_frame() {
  SternumFrame f;
  f.notch = Vec3::Zero();
  f.length_mm = 200.0;
  f.up = Vec3::UnitZ();
  f.front = Vec3::UnitY();
  f.lateral = Vec3::UnitX();
  return f;
}

}  // namespace breastfit::fit::test
