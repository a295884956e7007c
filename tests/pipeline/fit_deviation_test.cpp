#include "breastfit/pipeline/fit_deviation.h"

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"

namespace breastfit::pipeline {
namespace {

RegisterResult a_fit() {
  RegisterResult r;
  r.fit.vertices = Points::Zero(5, 3);
  for (int i = 0; i < 5; ++i) r.fit.vertices(i, 0) = 10.0 * i;
  r.model_landmarks_mm.points = {{"nipple_R", Vec3(0, 0, 0)}, {"nipple_L", Vec3(100, 0, 0)}};
  transfer::TransferredCurve c;
  c.name = "imf_R";
  c.points = Points::Zero(3, 3);
  c.points.col(0) << 0, 10, 20;
  r.drawings_on_scan = {c};
  return r;
}

TEST(FitDeviation, IsZeroForTheSameFitAndMeasuresEachPart) {
  const RegisterResult a = a_fit();
  const FitDeviation same = fit_deviation(a, a);
  EXPECT_EQ(same.surface_median_mm, 0);
  EXPECT_EQ(same.surface_max_mm, 0);
  EXPECT_EQ(same.landmarks_max_mm, 0);
  EXPECT_EQ(same.drawings_max_mm, 0);

  RegisterResult b = a;
  b.fit.vertices(4, 1) += 3.0;                          // one vertex 3 mm away
  b.fit.vertices.col(2).array() += 0.5;                 // all 0.5 mm up
  b.model_landmarks_mm.points[1].position.y() += 2.0;   // one landmark 2 mm away
  b.drawings_on_scan[0].points.col(1).array() += 1.5;   // the curve 1.5 mm sideways
  b.drawings_on_scan[0].points.col(0) << 0, 5, 20;      // resampled: points along it do not count
  const FitDeviation d = fit_deviation(a, b);
  EXPECT_NEAR(d.surface_median_mm, 0.5, 1e-12);
  EXPECT_NEAR(d.surface_max_mm, std::hypot(3.0, 0.5), 1e-12);
  EXPECT_NEAR(d.landmarks_max_mm, 2.0, 1e-12);
  EXPECT_NEAR(d.drawings_max_mm, 1.5, 1e-12);
}

TEST(FitDeviation, RefusesFitsOfDifferentTemplates) {
  RegisterResult b = a_fit();
  b.fit.vertices.conservativeResize(4, 3);
  EXPECT_THROW(fit_deviation(a_fit(), b), InvalidInput);
}

}  // namespace
}  // namespace breastfit::pipeline
