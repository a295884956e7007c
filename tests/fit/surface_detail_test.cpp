#include "breastfit/fit/surface_detail.h"

#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/normals.h"
#include "support/grid_mesh.h"

namespace breastfit::fit {
namespace {

// A square grid z = height(x, y), x and y in [-half, half] (half a multiple of step).
TriangleMesh grid(double half, double step, const std::function<double(double, double)>& height) {
  return test::grid_mesh(static_cast<int>(std::lround(half / step)), step, height);
}

double bump(double x, double y) { return 4.0 * std::exp(-(x * x + y * y) / (2 * 30.0 * 30.0)); }

TEST(SurfaceDetail, RecoversASmoothNormalDisplacement) {
  const TriangleMesh model = grid(100, 10, [](double, double) { return 0.0; });
  const ScanTarget scan(grid(110, 2.5, bump));
  const SurfaceDetail d = fit_surface_detail(model.V, model.F, scan, CorrespondenceOptions{}, SurfaceDetailOptions{});
  ASSERT_EQ(d.offsets.size(), model.V.rows());
  double worst = 0;
  for (Index i = 0; i < model.V.rows(); ++i) {
    const double x = model.V(i, 0), y = model.V(i, 1);
    if (std::abs(x) > 90 || std::abs(y) > 90) continue;  // the model's own border
    worst = std::max(worst, std::abs(d.offsets[i] - bump(x, y)));
    EXPECT_NEAR(d.vertices(i, 2), bump(x, y), 0.25) << "vertex " << i;
  }
  EXPECT_LT(worst, 0.25);
  EXPECT_NEAR(d.max_abs_mm, 4.0, 0.25);
  EXPECT_GT(d.kept, model.V.rows() / 2);
  // The vertices are the model displaced along its normals by the offsets.
  EXPECT_TRUE(d.vertices.isApprox(apply_surface_detail(model.V, model.F, d.offsets)));
}

TEST(SurfaceDetail, FadesToZeroWhereTheScanHasNoSurface) {
  const TriangleMesh model = grid(100, 10, [](double, double) { return 0.0; });
  // The scan covers only x < 0, raised by 2 mm.
  TriangleMesh half = grid(110, 2.5, [](double, double) { return 2.0; });
  Triangles kept(half.F.rows(), 3);
  Index k = 0;
  for (Index f = 0; f < half.F.rows(); ++f)
    if (half.V(half.F(f, 0), 0) < 0 && half.V(half.F(f, 1), 0) < 0 && half.V(half.F(f, 2), 0) < 0)
      kept.row(k++) = half.F.row(f);
  half.F = kept.topRows(k);
  const ScanTarget scan(half);
  const SurfaceDetail d = fit_surface_detail(model.V, model.F, scan, CorrespondenceOptions{}, SurfaceDetailOptions{});
  for (Index i = 0; i < model.V.rows(); ++i) {
    const double x = model.V(i, 0);
    if (x < -20) EXPECT_NEAR(d.offsets[i], 2.0, 0.2) << "supported vertex " << i;
    if (x > 70) EXPECT_LT(std::abs(d.offsets[i]), 0.2) << "unsupported vertex " << i;
  }
}

TEST(SurfaceDetail, IgnoresOutliersBeyondTheThresholdAndClampsOffsets) {
  const TriangleMesh model = grid(100, 10, [](double, double) { return 0.0; });
  const ScanTarget far(grid(110, 2.5, [](double, double) { return 30.0; }));
  const SurfaceDetail none = fit_surface_detail(model.V, model.F, far, CorrespondenceOptions{}, SurfaceDetailOptions{});
  EXPECT_EQ(none.kept, 0);
  EXPECT_LT(none.max_abs_mm, 1e-12);

  SurfaceDetailOptions o;
  o.max_offset_mm = 5;
  const ScanTarget raised(grid(110, 2.5, [](double, double) { return 8.0; }));
  const SurfaceDetail clamped = fit_surface_detail(model.V, model.F, raised, CorrespondenceOptions{}, o);
  EXPECT_NEAR(clamped.max_abs_mm, 5.0, 1e-9);
  EXPECT_NEAR(clamped.offsets.minCoeff(), 5.0, 1e-9);
}

TEST(SurfaceDetail, DisabledLeavesTheModelUnchanged) {
  const TriangleMesh model = grid(50, 10, [](double, double) { return 0.0; });
  const ScanTarget scan(grid(60, 2.5, bump));
  SurfaceDetailOptions o;
  o.enabled = false;
  const SurfaceDetail d = fit_surface_detail(model.V, model.F, scan, CorrespondenceOptions{}, o);
  EXPECT_EQ(d.offsets.size(), model.V.rows());
  EXPECT_EQ(d.offsets.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(d.vertices, model.V);
}

TEST(SurfaceDetail, IsDeterministic) {
  const TriangleMesh model = grid(100, 10, [](double, double) { return 0.0; });
  const ScanTarget scan(grid(110, 2.5, bump));
  const auto a = fit_surface_detail(model.V, model.F, scan, CorrespondenceOptions{}, SurfaceDetailOptions{});
  const auto b = fit_surface_detail(model.V, model.F, scan, CorrespondenceOptions{}, SurfaceDetailOptions{});
  EXPECT_EQ(a.offsets, b.offsets);
}

TEST(SurfaceDetail, ApplyRejectsAWrongNumberOfOffsets) {
  const TriangleMesh model = grid(20, 10, [](double, double) { return 0.0; });
  EXPECT_THROW(apply_surface_detail(model.V, model.F, Eigen::VectorXd::Zero(3)), InvalidInput);
}

}  // namespace
}  // namespace breastfit::fit
