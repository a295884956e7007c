#include "breastfit/metrics/distance_stats.h"

#include <algorithm>
#include <cmath>

namespace breastfit::metrics {

DistanceStats distance_stats(const std::vector<double>& distances) {
  DistanceStats s;
  s.n = static_cast<int>(distances.size());
  if (distances.empty()) return s;
  double sum = 0, sum_sq = 0;
  s.min = std::abs(distances[0]);
  s.max = s.min;
  for (double d : distances) {
    const double a = std::abs(d);
    sum += a;
    sum_sq += a * a;
    s.min = std::min(s.min, a);
    s.max = std::max(s.max, a);
  }
  s.mae = sum / s.n;
  s.rmse = std::sqrt(sum_sq / s.n);
  s.sd = std::sqrt(std::max(0.0, sum_sq / s.n - s.mae * s.mae));
  return s;
}

}  // namespace breastfit::metrics
