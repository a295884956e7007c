#include "breastfit/metrics/distance_stats_json.h"

namespace breastfit::metrics {

nlohmann::json to_json(const DistanceStats& s) {
  return {{"n", s.n}, {"mae", s.mae}, {"sd", s.sd}, {"max", s.max}, {"min", s.min}, {"rmse", s.rmse}};
}

}  // namespace breastfit::metrics
