#include "breastfit/fit/correspondence_schedule.h"

#include <gtest/gtest.h>

namespace breastfit::fit {
namespace {

TEST(CorrespondenceSchedule, DecaysGeometricallyFromStartToEndOverTheStages) {
  CorrespondenceOptions o;
  o.max_distance_start_mm = 40;
  o.max_distance_end_mm = 10;
  const CorrespondenceSchedule s(o, 2);
  EXPECT_DOUBLE_EQ(s.threshold(0, 0, 10), 40.0);
  EXPECT_DOUBLE_EQ(s.stage_end(0), 20.0);  // 40·(10/40)^(1/2)
  EXPECT_DOUBLE_EQ(s.stage_end(1), 10.0);
  EXPECT_DOUBLE_EQ(s.threshold(1, 9, 10), 10.0);
  double last = 1e9;
  for (int stage = 0; stage < 2; ++stage)
    for (int it = 0; it < 10; ++it) {
      const double t = s.threshold(stage, it, 10);
      EXPECT_LE(t, last + 1e-12);
      last = t;
    }
}

TEST(CorrespondenceSchedule, ReachesTheStageEndAfterTheRamp) {
  CorrespondenceOptions o;
  o.schedule_ramp = 0.5;
  const CorrespondenceSchedule s(o, 3);
  EXPECT_FALSE(s.at_stage_end(1, 4, 10));
  EXPECT_TRUE(s.at_stage_end(1, 5, 10));
  EXPECT_TRUE(s.at_stage_end(1, 9, 10));
  o.schedule_ramp = 1.0;
  const CorrespondenceSchedule full(o, 3);
  EXPECT_FALSE(full.at_stage_end(1, 9, 10));
  EXPECT_TRUE(full.at_stage_end(1, 10, 10));
}

}  // namespace
}  // namespace breastfit::fit
