#include "breastfit/transfer/polyline.h"

#include <gtest/gtest.h>

#include <cmath>

#include "breastfit/core/errors.h"

namespace breastfit::transfer {
namespace {

Points circle(int n, double r) {
  Points P(n, 3);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    P.row(i) << r * std::cos(a), r * std::sin(a), 0.0;
  }
  return P;
}

TEST(Polyline, LengthOpenAndClosed) {
  Points P(3, 3);
  P << 0, 0, 0, 3, 0, 0, 3, 4, 0;
  EXPECT_DOUBLE_EQ(polyline_length(P, false), 7.0);
  EXPECT_DOUBLE_EQ(polyline_length(P, true), 12.0);
}

TEST(Polyline, ResampleOpenKeepsEndsAndEqualSpacing) {
  Points P(3, 3);
  P << 0, 0, 0, 10.5, 0, 0, 10.5, 10, 0;
  const Points R = resample_polyline(P, false, 1.0);
  EXPECT_EQ(R.rows(), 22);  // 20.5 mm → 21 intervals
  EXPECT_TRUE(R.row(0).isApprox(P.row(0)));
  EXPECT_TRUE(R.row(R.rows() - 1).isApprox(P.row(2)));
  // the corner is cut (by at most (2 − √2)/2 of an interval), straight parts are exact
  EXPECT_LE(polyline_length(R, false), 20.5 + 1e-9);
  EXPECT_GT(polyline_length(R, false), 20.5 - 0.3);
  for (Eigen::Index i = 1; i < R.rows(); ++i) EXPECT_LE((R.row(i) - R.row(i - 1)).norm(), 1.0);
}

TEST(Polyline, ResampleClosedStaysClosedAndUniform) {
  const Points P = circle(12, 50.0);
  const Points R = resample_polyline(P, true, 1.0);
  const double len = polyline_length(P, true);
  EXPECT_EQ(R.rows(), std::llround(len));
  EXPECT_TRUE(R.row(0).isApprox(P.row(0)));
  // no repeated first point; the closing gap is one step like the others
  const double step = len / static_cast<double>(R.rows());
  EXPECT_NEAR((R.row(0) - R.row(R.rows() - 1)).norm(), step, 0.05);
  // inscribed in the 12-gon: only the 12 corners are cut, each by less than 0.3 of an interval
  EXPECT_LE(polyline_length(R, true), len + 1e-9);
  EXPECT_GT(polyline_length(R, true), len - 12 * 0.3);
  for (Eigen::Index i = 0; i < R.rows(); ++i) EXPECT_LT(point_polyline_distance(R.row(i).transpose(), P, true), 1e-9);
  EXPECT_THROW(resample_polyline(P, true, 0.0), InvalidInput);
}

TEST(Polyline, LaplacianKeepsOpenEndsAndShrinksNoise) {
  Points P(5, 3);
  P << 0, 0, 0, 1, 1, 0, 2, 0, 0, 3, 1, 0, 4, 0, 0;
  const Points S = laplacian_smooth(P, false, 0.5);
  EXPECT_TRUE(S.row(0).isApprox(P.row(0)));
  EXPECT_TRUE(S.row(4).isApprox(P.row(4)));
  EXPECT_NEAR(S(1, 1), 0.5, 1e-12);
  EXPECT_NEAR(S(2, 1), 0.5, 1e-12);
  std::vector<bool> fixed{false, true, false, false, false};
  const Points F = laplacian_smooth(P, false, 0.5, &fixed);
  EXPECT_TRUE(F.row(1).isApprox(P.row(1)));
}

TEST(Polyline, CurveDistanceOfShiftedCircle) {
  const Points A = circle(200, 40.0);
  Points B = A;
  B.col(2).array() += 2.0;
  const CurveDistance same = curve_distance(A, true, A, true);
  EXPECT_NEAR(same.mean_sym, 0.0, 1e-9);
  const CurveDistance d = curve_distance(A, true, B, true);
  EXPECT_NEAR(d.mean_sym, 2.0, 1e-3);
  EXPECT_NEAR(d.hausdorff, 2.0, 1e-3);
  EXPECT_NEAR(point_polyline_distance(Vec3(0, 0, 0), A, true), 40.0, 0.1);
}

}  // namespace
}  // namespace breastfit::transfer
