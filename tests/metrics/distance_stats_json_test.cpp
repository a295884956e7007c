#include "breastfit/metrics/distance_stats_json.h"

#include <gtest/gtest.h>

namespace breastfit::metrics {
namespace {

TEST(DistanceStatsJson, EveryStatisticByName) {
  const DistanceStats s = distance_stats({1.0, -3.0, 2.0, 2.0});
  const nlohmann::json j = to_json(s);
  EXPECT_EQ(j.size(), 6u);
  EXPECT_EQ(j["n"], 4);
  EXPECT_EQ(j["mae"], s.mae);
  EXPECT_EQ(j["sd"], s.sd);
  EXPECT_EQ(j["max"], 3.0);
  EXPECT_EQ(j["min"], 1.0);
  EXPECT_EQ(j["rmse"], s.rmse);
}

}  // namespace
}  // namespace breastfit::metrics
