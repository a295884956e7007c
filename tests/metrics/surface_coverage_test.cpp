#include "breastfit/metrics/surface_coverage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "breastfit/mesh/normals.h"
#include "breastfit/metrics/fit_errors.h"
#include "breastfit/model/pose_evaluator.h"
#include "breastfit/synth/synth_case.h"
#include "support/default_template.h"

namespace breastfit::metrics {
namespace {

// A synthetic standing case without misalignment (scanner Y = up), and the subject's own model
// posed with the true parameters: a fit as good as the model allows.
struct Case {
  synth::SynthCase c;
  TriangleMesh fitted;
};

const Case& the_case() {
  static const Case k = [] {
    const auto& model = *test::default_template();
    synth::SynthOptions o;
    o.seed = 3;
    o.misalign_rotation_deg = 0;
    o.misalign_translation_m = 0;
    Case k;
    k.c = synth::make_case(model, o);
    k.fitted.V = model::pose_vertices(model, k.c.true_params_scan);
    k.fitted.F = model.rest.F;
    return k;
  }();
  return k;
}

// The scan without its triangles that reach below height y (a jagged cut, as a real clipped scan).
TriangleMesh clipped_below(const TriangleMesh& scan, double y) {
  TriangleMesh out;
  out.V = scan.V;
  std::vector<Eigen::Vector3i> kept;
  for (Index f = 0; f < scan.F.rows(); ++f)
    if (scan.V(scan.F(f, 0), 1) > y && scan.V(scan.F(f, 1), 1) > y && scan.V(scan.F(f, 2), 1) > y)
      kept.emplace_back(scan.F.row(f).transpose());
  out.F.resize(static_cast<Index>(kept.size()), 3);
  for (size_t i = 0; i < kept.size(); ++i) out.F.row(static_cast<Index>(i)) = kept[i].transpose();
  return out;
}

// The same scan with a flat cap over its cut (facing down, 100 mm beyond the body on every side,
// not joined to it), as a scan closed at its lower cut: there is no open border at the cut.
TriangleMesh capped_at(const TriangleMesh& clipped, double y) {
  TriangleMesh out = clipped;
  const Eigen::RowVector3d lo = clipped.V.colwise().minCoeff(), hi = clipped.V.colwise().maxCoeff();
  const Index n = out.V.rows();
  out.V.conservativeResize(n + 4, 3);
  out.V.row(n) << lo.x() - 100, y, lo.z() - 100;
  out.V.row(n + 1) << hi.x() + 100, y, lo.z() - 100;
  out.V.row(n + 2) << hi.x() + 100, y, hi.z() + 100;
  out.V.row(n + 3) << lo.x() - 100, y, hi.z() + 100;
  const Index f = out.F.rows();
  out.F.conservativeResize(f + 2, 3);
  out.F.row(f) << n, n + 1, n + 2;  // normal −y
  out.F.row(f + 1) << n, n + 2, n + 3;
  return out;
}

double height_of(const std::vector<NamedPoint>& points, const std::string& name) {
  for (const auto& p : points)
    if (p.name == name) return p.position.y();
  ADD_FAILURE() << "no landmark " << name;
  return 0;
}

TEST(SurfaceCoverage, AClippedScanCountsOnlyTheRegionItCovers) {
  const Case& k = the_case();
  const fit::ScanTarget full(k.c.scan);
  const SurfaceCoverage all = surface_coverage(k.fitted, full);
  ASSERT_GT(all.covered_count, 0);
  EXPECT_GT(all.fraction(), 0.3);  // the scanner sees the front and the sides, not the back
  EXPECT_LT(all.stats().mae, 4.0);

  // Cut far above the waist, between the nipples and the sternal notch: the band below the cut
  // is the real scan's problem (issue: MAE 11 mm, max 150 mm while the front fits within 2 mm).
  const double y_cut = 0.5 * (height_of(k.c.truth_landmarks, "nipple_R") + height_of(k.c.truth_landmarks, "sternal_notch"));
  const fit::ScanTarget cut(clipped_below(k.c.scan, y_cut));
  const SurfaceCoverage part = surface_coverage(k.fitted, cut);
  EXPECT_NEAR(part.stats().mae, all.stats().mae, 0.5);
  EXPECT_LT(part.stats().max, all.stats().max + 1.0);

  // The fraction drops by the covered vertices that lie below the cut.
  Index covered_above = 0;
  for (Index i = 0; i < k.fitted.V.rows(); ++i)
    if (all.covered[static_cast<size_t>(i)] && k.fitted.V(i, 1) > y_cut + 5.0) ++covered_above;
  const double expected = static_cast<double>(covered_above) / static_cast<double>(k.fitted.V.rows());
  EXPECT_LT(part.fraction(), 0.6 * all.fraction());
  EXPECT_NEAR(part.fraction(), expected, 0.05);

  // Closed at the cut, the scan has no border there: the border-only rule counts the model's
  // band below the cut (the real clipped scan's 11 mm MAE), the coverage rule does not.
  const fit::ScanTarget capped(capped_at(clipped_below(k.c.scan, y_cut), y_cut));
  const DistanceStats border_only = distance_stats(surface_distances(k.fitted.V, capped));
  const SurfaceCoverage closed = surface_coverage(k.fitted, capped);
  std::printf("MAE all %.2f, clipped %.2f, capped %.2f (border-only rule %.2f, max %.1f); coverage %.2f, %.2f, %.2f\n",
              all.stats().mae, part.stats().mae, closed.stats().mae, border_only.mae, border_only.max, all.fraction(),
              part.fraction(), closed.fraction());
  EXPECT_GT(border_only.mae, closed.stats().mae + 2.0);
  EXPECT_NEAR(closed.stats().mae, all.stats().mae, 0.5);
  EXPECT_NEAR(closed.fraction(), expected, 0.05);
}

TEST(SurfaceCoverage, AModelFarFromTheScanIsNotCovered) {
  const Case& k = the_case();
  const fit::ScanTarget full(k.c.scan);
  TriangleMesh inflated = k.fitted;
  inflated.V += 40.0 * mesh::vertex_normals(k.fitted);  // 40 mm outside the scan everywhere
  const SurfaceCoverage c = surface_coverage(inflated, full);
  EXPECT_LT(c.fraction(), 0.05);  // a few vertices in concave folds come closer
  EXPECT_EQ(c.distance_mm.size(), static_cast<size_t>(k.fitted.V.rows()));
  // The searches stop at max_distance_mm: a vertex farther than that has no distance (+∞).
  int far = 0;
  for (size_t i = 0; i < c.distance_mm.size(); ++i) {
    if (c.distance_mm[i] <= c.options.max_distance_mm) continue;
    EXPECT_TRUE(std::isinf(c.distance_mm[i])) << c.distance_mm[i];
    EXPECT_FALSE(c.covered[i]);
    ++far;
  }
  EXPECT_GT(far, k.fitted.V.rows() / 2);
}

TEST(SurfaceCoverage, WarmStartsFromAnotherPassChangeNothingButTheSpeed) {
  const Case& k = the_case();
  const fit::ScanTarget full(k.c.scan);
  std::vector<Index> faces;
  const SurfaceCoverage first = surface_coverage(k.fitted, full, {}, &faces);
  ASSERT_EQ(faces.size(), static_cast<size_t>(k.fitted.V.rows()));
  TriangleMesh moved = k.fitted;
  moved.V += 2.0 * mesh::vertex_normals(k.fitted);  // as the model without its surface detail
  const SurfaceCoverage cold = surface_coverage(moved, full);
  const SurfaceCoverage warm = surface_coverage(moved, full, {}, &faces);
  ASSERT_EQ(warm.distance_mm.size(), cold.distance_mm.size());
  for (size_t i = 0; i < cold.distance_mm.size(); ++i)  // a tie between two faces may differ in the last bits
    if (!std::isinf(cold.distance_mm[i])) EXPECT_NEAR(warm.distance_mm[i], cold.distance_mm[i], 1e-9) << i;
  EXPECT_EQ(warm.covered, cold.covered);
  EXPECT_NE(cold.distance_mm, first.distance_mm);
}

}  // namespace
}  // namespace breastfit::metrics
