#pragma once
/// \file Summary statistics of absolute distances (the paper's Table 1 columns).
#include <vector>

namespace breastfit::metrics {

struct DistanceStats {
  int n = 0;
  double mae = 0;   ///< mean absolute distance, mm
  double sd = 0;    ///< population standard deviation, mm
  double max = 0;   ///< mm
  double min = 0;   ///< mm
  double rmse = 0;  ///< mm
};

/// Statistics of |d| over `distances` (all zero with n = 0 when empty).
DistanceStats distance_stats(const std::vector<double>& distances);

}  // namespace breastfit::metrics
