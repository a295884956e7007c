#include "breastfit/fit/sternum_length.h"

namespace breastfit::fit {

double sternum_length_by_nipples_mm(const Vec3& notch, const Vec3& nipple_R, const Vec3& nipple_L,
                                    const SternumLengthOptions& options) {
  const double d = 0.5 * ((nipple_R - notch).norm() + (nipple_L - notch).norm());
  return options.slope * d + options.offset_mm;
}

std::optional<Vec3> xiphoid_by_nipples(const Vec3& notch, const Vec3& nipple_R, const Vec3& nipple_L,
                                       const Vec3& fitted_xiphoid, const SternumLengthOptions& options) {
  const Vec3 along = fitted_xiphoid - notch;
  const double fitted_length = along.norm();
  if (!(fitted_length > 0) || !along.allFinite()) return std::nullopt;
  const Vec3 placed = notch + along / fitted_length * sternum_length_by_nipples_mm(notch, nipple_R, nipple_L, options);
  if (!placed.allFinite() || (placed - fitted_xiphoid).norm() > options.max_shift_mm) return std::nullopt;
  return placed;
}

}  // namespace breastfit::fit
