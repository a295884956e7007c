#include "breastfit/transfer/breast_measurements.h"

#include <gtest/gtest.h>

#include "support/default_template.h"

#include <cmath>
#include <cstdio>

#include "breastfit/core/errors.h"
#include "breastfit/model/pose_evaluator.h"
#include "breastfit/model/template_library.h"
#include "support/grid_mesh.h"

namespace breastfit::transfer {
namespace {

TriangleMesh grid(int n, double h) { return test::grid_mesh(n, h); }

TEST(BreastMeasurements, SphericalCapOnAPlane) {
  TriangleMesh g = grid(60, 1.0);  // 120 x 120 mm
  const double R = 50, a = 40;     // sphere radius, cap base radius
  const double h = R - std::sqrt(R * R - a * a);
  std::vector<Index> region;
  for (Index v = 0; v < g.num_vertices(); ++v) {
    const double r = g.V.row(v).head<2>().norm();
    if (r < a) {
      g.V(v, 2) = std::sqrt(R * R - r * r) - (R - h);
      region.push_back(v);
    }
  }
  const double exact = M_PI * h * h * (3 * R - h) / 3.0;
  for (ChestWallFill fill : {ChestWallFill::Membrane, ChestWallFill::ThinPlate}) {
    const RegionVolume rv = region_volume(g, region, {.fill = fill, .margin_mm = 0});
    EXPECT_NEAR(rv.volume_mm3, exact, 0.02 * exact);
    // the fill of a flat chest is the plane
    double max_z = 0;
    for (Index v : region) max_z = std::max(max_z, std::abs(rv.chest_wall(v, 2)));
    EXPECT_LT(max_z, 1e-6);
  }
}

TEST(BreastMeasurements, BumpOnACurvedChestWall) {
  // Cylinder of radius Rc around the z axis (outward normals), bump f(θ, z) along the radius.
  const double Rc = 150, sigma = 20;
  const int nt = 240, nz = 161;
  const double dz = 1.0, dth = 0.6 * M_PI / (nt - 1);  // 108° of arc, 160 mm tall
  TriangleMesh c;
  c.V.resize(nt * nz, 3);
  std::vector<Index> region;
  double expected = 0;
  auto bump = [&](double s, double z) {
    const double d2 = s * s + z * z;
    return d2 < 9 * sigma * sigma ? 12.0 * std::exp(-d2 / (2 * sigma * sigma)) : 0.0;
  };
  for (int i = 0; i < nt; ++i)
    for (int k = 0; k < nz; ++k) {
      const double th = -0.3 * M_PI + i * dth, z = (k - nz / 2) * dz;
      const double f = bump(Rc * th, z);
      const double r = Rc + f;
      c.V.row(i * nz + k) << r * std::cos(th), r * std::sin(th), z;
      if (f > 0) region.push_back(i * nz + k);
      expected += 0.5 * ((Rc + f) * (Rc + f) - Rc * Rc) * dth * dz;  // ∫∫ (r² − Rc²)/2 dθ dz
    }
  c.F.resize(2 * (nt - 1) * (nz - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < nt; ++i)
    for (int k = 0; k + 1 < nz; ++k) {
      const int a = i * nz + k, b = (i + 1) * nz + k, cc = (i + 1) * nz + k + 1, d = i * nz + k + 1;
      // outward (radial) orientation: (θ, z) → counter-clockwise seen from outside
      c.F.row(f++) << a, b, cc;
      c.F.row(f++) << a, cc, d;
    }
  const RegionVolume rv = region_volume(c, region, {.fill = ChestWallFill::ThinPlate, .margin_mm = 0});
  const RegionVolume membrane = region_volume(c, region, {.fill = ChestWallFill::Membrane, .margin_mm = 0});
  // a margin anchors the thin plate further out on the same wall: same volume
  const RegionVolume with_margin = region_volume(c, region, {.fill = ChestWallFill::ThinPlate, .margin_mm = 20});
  EXPECT_NEAR(with_margin.volume_mm3, expected, 0.06 * expected);
  std::printf("cylinder bump: %.0f mm3 thin plate, %.0f mm3 membrane, %.0f mm3 expected\n", rv.volume_mm3,
              membrane.volume_mm3, expected);
  EXPECT_NEAR(rv.volume_mm3, expected, 0.03 * expected);
  // the thin plate follows the curved wall (not the chord)
  double worst = 0;
  for (Index v : region) worst = std::max(worst, std::abs(rv.chest_wall.row(v).head<2>().norm() - Rc));
  EXPECT_LT(worst, 1.0);
  // the membrane sags under the convex wall: more volume, bounded by the cap of the cylinder
  // over the footprint (sagitta ≈ r²/(2 Rc) with r = 3σ)
  EXPECT_GT(membrane.volume_mm3, rv.volume_mm3);
  const double r = 3 * sigma;
  EXPECT_LT(membrane.volume_mm3 - expected, M_PI * r * r * (r * r / (2 * Rc)));
}

TEST(BreastMeasurements, RejectsBadRegions) {
  const TriangleMesh g = grid(3, 1.0);
  EXPECT_THROW(region_volume(g, {}), InvalidInput);
  EXPECT_THROW(region_volume(g, {1000}), InvalidInput);
  std::vector<Index> all(static_cast<size_t>(g.num_vertices()));
  for (Index v = 0; v < g.num_vertices(); ++v) all[static_cast<size_t>(v)] = v;
  EXPECT_THROW(region_volume(g, all), InvalidInput);
}

const model::RiggedModel& torso() { return *test::default_template(); }

TEST(BreastMeasurements, TemplateIsSymmetricAndTracksBreastShapes) {
  const model::RiggedModel& m = torso();
  model::PoseParams p = model::PoseParams::identity(m);
  const BreastMeasurements rest = measure_breasts(m, model::pose_vertices(m, p));
  ASSERT_TRUE(rest.right.volume_ml && rest.left.volume_ml);
  std::printf("template: volume R %.0f ml L %.0f ml, notch-nipple %.0f mm, nipple-imf %.0f mm, inter-nipple %.0f mm\n",
              *rest.right.volume_ml, *rest.left.volume_ml, *rest.right.notch_to_nipple_mm, *rest.right.nipple_to_imf_mm,
              *rest.inter_nipple_mm);
  EXPECT_GT(*rest.right.volume_ml, 50.0);
  EXPECT_LT(*rest.right.volume_ml, 2000.0);
  EXPECT_NEAR(*rest.volume_ratio, 1.0, 0.05);
  EXPECT_NEAR(*rest.notch_to_nipple_ratio, 1.0, 0.05);
  EXPECT_NEAR(*rest.nipple_to_imf_ratio, 1.0, 0.1);
  EXPECT_GT(*rest.right.notch_to_nipple_mm, 120.0);
  EXPECT_LT(*rest.right.notch_to_nipple_mm, 320.0);
  EXPECT_GT(*rest.inter_nipple_mm, 120.0);
  EXPECT_TRUE(rest.warnings.empty()) << rest.warnings.front();

  // Same numbers after a rigid motion and in any frame.
  model::PoseParams moved = p;
  moved.global.rotation = Quat(Eigen::AngleAxisd(0.7, Vec3(0.3, 1, 0.2).normalized()));
  moved.global.translation = Vec3(100, -40, 300);
  const BreastMeasurements rigid = measure_breasts(m, model::pose_vertices(m, moved));
  EXPECT_NEAR(*rigid.right.volume_ml, *rest.right.volume_ml, 1e-6 * *rest.right.volume_ml);
  EXPECT_NEAR(*rigid.left.nipple_to_imf_mm, *rest.left.nipple_to_imf_mm, 1e-6);

  // A larger right breast (a volume-like blendshape on the right side only) changes the ratio.
  const auto k = m.blendshape_index("breast_volume_R");
  if (!k) GTEST_SKIP() << "template has no breast_volume_R";
  p.alpha[*k] = std::min(1.0, m.blendshapes[*k].hi);
  const BreastMeasurements bigger = measure_breasts(m, model::pose_vertices(m, p));
  EXPECT_GT(*bigger.right.volume_ml, 1.1 * *rest.right.volume_ml);
  EXPECT_NEAR(*bigger.left.volume_ml, *rest.left.volume_ml, 0.05 * *rest.left.volume_ml);
  EXPECT_LT(*bigger.volume_ratio, 0.95);
}

// The two sides measured apart (measure_breast_side, as a warm re-fit runs them as tasks of its
// own) and joined give measure_breasts' numbers and warnings, bit for bit; a bad side is refused.
TEST(BreastMeasurements, SidesMeasuredApartAreMeasureBreasts) {
  const model::RiggedModel& m = torso();
  model::PoseParams p = model::PoseParams::identity(m);
  if (const auto k = m.blendshape_index("breast_volume_R")) p.alpha[*k] = std::min(0.5, m.blendshapes[*k].hi);
  const Points V = model::pose_vertices(m, p);
  const BreastMeasurements both = measure_breasts(m, V, {}, nullptr, 2);
  BreastSideMeasurement left = measure_breast_side(m, V, 'L');
  BreastSideMeasurement right = measure_breast_side(m, V, 'R');
  const BreastMeasurements joined = join_breast_sides(m, V, std::move(right), std::move(left));
  ASSERT_TRUE(both.right.volume_ml && both.left.volume_ml && joined.right.volume_ml && joined.left.volume_ml);
  EXPECT_EQ(*joined.right.volume_ml, *both.right.volume_ml);
  EXPECT_EQ(*joined.left.volume_ml, *both.left.volume_ml);
  EXPECT_NE(*joined.right.volume_ml, *joined.left.volume_ml);  // the sides are not exchanged
  EXPECT_EQ(*joined.volume_ratio, *both.volume_ratio);
  EXPECT_EQ(*joined.right.nipple_to_imf_mm, *both.right.nipple_to_imf_mm);
  EXPECT_EQ(*joined.left.notch_to_nipple_mm, *both.left.notch_to_nipple_mm);
  EXPECT_EQ(*joined.inter_nipple_mm, *both.inter_nipple_mm);
  EXPECT_EQ(joined.warnings, both.warnings);
  EXPECT_THROW(measure_breast_side(m, V, 'X'), InvalidInput);
  EXPECT_THROW(measure_breast_side(m, V.topRows(10), 'R'), InvalidInput);
}

}  // namespace
}  // namespace breastfit::transfer

// The volume of a real fit against the subject's own (the true parameters pose the same
// template: same region, same chest-wall rule), on synthetic cases: the error the fit adds.
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/synth/synth_case.h"
#include "support/synth_request.h"

namespace breastfit::transfer {
namespace {

TEST(BreastMeasurements, FittedVolumeOnSynthCases) {
  double sum_abs = 0;
  int n = 0;
  for (std::uint64_t seed : {31u, 32u, 33u, 34u}) {
    synth::SynthOptions o;
    o.seed = seed;
    o.pose = seed % 2 ? synth::PoseType::Standing : synth::PoseType::Supine;
    const synth::SynthCase c = synth::make_case(torso(), o);
    const pipeline::RegisterResult r = pipeline::register_scan(test::synth_request(c));
    ASSERT_TRUE(r.usable());
    const BreastMeasurements fitted = measure_breasts(torso(), r.fit.vertices);
    const BreastMeasurements truth = measure_breasts(torso(), model::pose_vertices(torso(), c.true_params_scan));
    for (int side = 0; side < 2; ++side) {
      const double vf = *(side ? fitted.left : fitted.right).volume_ml;
      const double vt = *(side ? truth.left : truth.right).volume_ml;
      const double nf = *(side ? fitted.left : fitted.right).notch_to_nipple_mm;
      const double nt = *(side ? truth.left : truth.right).notch_to_nipple_mm;
      std::printf("seed %llu %s: volume truth %.0f ml fit %.0f ml (%+.1f %%), notch-nipple truth %.1f fit %.1f mm\n",
                  static_cast<unsigned long long>(seed), side ? "L" : "R", vt, vf, 100 * (vf - vt) / vt, nt, nf);
      sum_abs += std::abs(vf - vt) / vt;
      ++n;
      EXPECT_LT(std::abs(vf - vt) / vt, 0.35);
      EXPECT_LT(std::abs(nf - nt), 10.0);
    }
  }
  std::printf("mean |volume error| %.1f %%\n", 100 * sum_abs / n);
  EXPECT_LT(sum_abs / n, 0.2);
}

}  // namespace
}  // namespace breastfit::transfer
