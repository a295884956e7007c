#include "breastfit/synth/truth_curves.h"

#include <gtest/gtest.h>

#include <numbers>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/subdivision.h"

namespace breastfit::synth {
namespace {

TriangleMesh sphere(double r) {
  TriangleMesh m;
  m.V.resize(6, 3);
  m.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  m.F.resize(8, 3);
  m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  for (int k = 0; k < 5; ++k) m = mesh::subdivide(m, false);
  for (Index v = 0; v < m.num_vertices(); ++v) m.V.row(v) = r * m.V.row(v).normalized();
  return m;
}

TEST(TruthCurves, ClosedCurveOnTheSurfaceEveryMillimetre) {
  const TriangleMesh s = sphere(100.0);
  const spatial::ClosestPointIndex index(s);
  // A 64-gon around the equator (corners on the sphere, ~10 mm apart like template drawings).
  Points P(64, 3);
  for (int i = 0; i < 64; ++i) {
    const double a = 2 * std::numbers::pi * i / 64;
    P.row(i) << 100 * std::cos(a), 100 * std::sin(a), 0;
  }
  const Points R = resample_on_surface(P, true, index, 1.0);
  EXPECT_NEAR(R.rows(), 2 * std::numbers::pi * 100, 0.02 * 2 * std::numbers::pi * 100);
  EXPECT_LT((R.row(0) - P.row(0)).norm(), 1e-6);  // starts at the first point
  for (Index i = 0; i < R.rows(); ++i) {
    EXPECT_LT(index.closest(R.row(i).transpose()).distance(), 1e-9);
    const Index j = (i + 1) % R.rows();
    const double step = (R.row(j) - R.row(i)).norm();
    EXPECT_GT(step, 0.9);
    EXPECT_LT(step, 1.1);
  }
}

TEST(TruthCurves, OpenCurveKeepsBothEnds) {
  const TriangleMesh s = sphere(50.0);
  const spatial::ClosestPointIndex index(s);
  Points P(17, 3);  // a quarter great circle, ~5 mm apart
  for (int i = 0; i <= 16; ++i) {
    const double a = 0.5 * std::numbers::pi * i / 16;
    P.row(i) << 50 * std::cos(a), 50 * std::sin(a), 0;
  }
  const Points R = resample_on_surface(P, false, index, 1.0);
  EXPECT_LT((R.row(0) - P.row(0)).norm(), 1e-6);
  EXPECT_LT((R.row(R.rows() - 1) - P.row(16)).norm(), 1e-6);
  EXPECT_NEAR(R.rows() - 1, 0.5 * std::numbers::pi * 50, 2.0);
  EXPECT_THROW(resample_on_surface(P.topRows(1), false, index, 1.0), InvalidInput);
  EXPECT_THROW(resample_on_surface(P, false, index, 0.0), InvalidInput);
}

}  // namespace
}  // namespace breastfit::synth
