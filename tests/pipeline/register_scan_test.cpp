// register_scan's selection of the landmarks the fit's initialisation places the template by
// (RegisterResult::initial_landmarks, what the report's figures are set up from).
#include "breastfit/pipeline/register_scan.h"

#include <gtest/gtest.h>

#include "breastfit/fit/registration.h"
#include "pipeline/report_test_case.h"

namespace breastfit {
namespace {

std::vector<fit::LandmarkTarget> four_targets() {
  std::vector<std::pair<std::string, Vec3>> lm = {{"sternal_notch", Vec3(0, 0, 0)},
                                                  {"xiphoid", Vec3(0, 0, -180)},
                                                  {"nipple_R", Vec3(-100, -60, -150)},
                                                  {"nipple_L", Vec3(100, -60, -150)}};
  return fit::match_landmarks(test::report_test_model(), lm);
}

TEST(InitializationLandmarks, AsTheFitSelectsThem) {
  fit::FitOptions o;
  EXPECT_EQ(pipeline::initialization_landmarks(four_targets(), o).size(), 4u);
  o.max_landmarks = 3;
  const auto three = pipeline::initialization_landmarks(four_targets(), o);
  ASSERT_EQ(three.size(), 3u);
  EXPECT_EQ(three[2].name, four_targets()[2].name);  // the first ones, in order
  o.max_landmarks = -1;
  o.use_landmarks = false;
  EXPECT_TRUE(pipeline::initialization_landmarks(four_targets(), o).empty());
}

TEST(InitializationLandmarks, KeptInTheResult) {
  const auto& r = test::report_test_result();
  EXPECT_EQ(r.initial_landmarks.size(), static_cast<size_t>(r.fit.summary.landmarks_used));
  EXPECT_EQ(r.fit.summary.initialization, "landmarks");
}

}  // namespace
}  // namespace breastfit
