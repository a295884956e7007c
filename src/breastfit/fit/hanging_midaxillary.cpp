#include "breastfit/fit/hanging_midaxillary.h"

#include <cmath>
#include <limits>

namespace breastfit::fit {

std::optional<Vec3> hanging_midaxillary_on_scan(const Points& scan_vertices, const Vec3& fitted,
                                                const SternumFrame& frame, const HangingMidaxillaryOptions& o) {
  if (!(frame.length_mm > 0)) return std::nullopt;
  const SternumCoordinates f = sternum_coordinates(frame, fitted);
  const double height = -o.drop * frame.length_mm, front = f.front + o.front_shift_mm;
  const double w = o.strip_half_width_mm;
  Index best = -1;
  double nearest = std::numeric_limits<double>::infinity();
  for (Index i = 0; i < scan_vertices.rows(); ++i) {
    const SternumCoordinates p = sternum_coordinates(frame, scan_vertices.row(i).transpose());
    if (std::abs(p.height - height) > w || std::abs(p.front - front) > w) continue;
    const double across = std::abs(p.lateral - f.lateral);
    if (across < nearest) {
      nearest = across;
      best = i;
    }
  }
  if (best < 0) return std::nullopt;
  const Vec3 found = scan_vertices.row(best).transpose();
  if ((found - fitted).norm() > o.max_shift_mm) return std::nullopt;
  return found;
}

}  // namespace breastfit::fit
