#include "breastfit/metrics/distance_stats.h"

#include <gtest/gtest.h>

#include <cmath>

namespace breastfit::metrics {
namespace {

TEST(DistanceStats, MatchesHandComputedValues) {
  const auto s = distance_stats({1.0, -3.0, 2.0, 2.0});
  EXPECT_EQ(s.n, 4);
  EXPECT_DOUBLE_EQ(s.mae, 2.0);
  EXPECT_DOUBLE_EQ(s.max, 3.0);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_NEAR(s.sd, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(s.rmse, std::sqrt(18.0 / 4), 1e-12);
}

TEST(DistanceStats, EmptyIsAllZero) {
  const auto s = distance_stats({});
  EXPECT_EQ(s.n, 0);
  EXPECT_EQ(s.mae, 0.0);
}

}  // namespace
}  // namespace breastfit::metrics
