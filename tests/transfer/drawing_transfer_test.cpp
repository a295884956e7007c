#include "breastfit/transfer/drawing_transfer.h"

#include <gtest/gtest.h>

#include "support/default_template.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/model/pose_evaluator.h"
#include "breastfit/model/template_library.h"
#include "breastfit/spatial/closest_point_index.h"
#include "breastfit/synth/synth_case.h"
#include "breastfit/transfer/polyline.h"

namespace breastfit::transfer {
namespace {

const model::RiggedModel& torso() { return *test::default_template(); }

synth::SynthOptions clean_options(std::uint64_t seed) {
  synth::SynthOptions o;
  o.seed = seed;
  o.artifacts.white_noise_mm = 0;
  o.artifacts.tangential_jitter_mm = 0;
  o.artifacts.lowfreq_noise_mm = 0;
  o.artifacts.n_fragments = 0;
  o.artifacts.n_holes = 0;
  return o;
}

const Curve& truth_curve(const synth::SynthCase& c, const std::string& name) {
  for (const auto& t : c.truth_curves)
    if (t.name == name) return t;
  throw std::runtime_error("no truth curve " + name);
}

// The subject's own parameters pose the template onto the case (scan frame, mm): a perfect fit
// up to the case's deformation outside the model space.
Points true_fit(const synth::SynthCase& c) { return model::pose_vertices(torso(), c.true_params_scan); }

TEST(DrawingTransfer, MatchesSynthTruthWithoutNoise) {
  const synth::SynthCase c = synth::make_case(torso(), clean_options(3));
  ASSERT_EQ(c.units, "mm");
  const fit::ScanTarget scan(c.scan);
  const auto curves = transfer_drawings(torso(), true_fit(c), scan);
  ASSERT_EQ(curves.size(), torso().drawings.size());
  for (const auto& tc : curves) {
    const Curve& truth = truth_curve(c, tc.name);
    const CurveDistance d = curve_distance(tc.points, tc.closed, truth.points, truth.closed);
    std::printf("%-18s mean_sym %.2f mm  hausdorff %.2f mm  supported %.2f  model-scan %.2f mm\n", tc.name.c_str(),
                d.mean_sym, d.hausdorff, tc.supported_fraction, tc.mean_model_to_scan_mm);
    EXPECT_LT(d.mean_sym, 3.0) << tc.name;
    EXPECT_EQ(tc.closed, truth.closed) << tc.name;
    EXPECT_EQ(tc.supported.size(), static_cast<size_t>(tc.points.rows()));
    EXPECT_NEAR(tc.length_mm, polyline_length(tc.points, tc.closed), 1e-9);
    // ~1 mm spacing, closed curves without a repeated end point
    for (Eigen::Index i = 1; i < tc.points.rows(); ++i) EXPECT_LT((tc.points.row(i) - tc.points.row(i - 1)).norm(), 2.0);
    if (tc.closed) EXPECT_LT((tc.points.row(0) - tc.points.row(tc.points.rows() - 1)).norm(), 2.0);
  }
}

TEST(DrawingTransfer, ProjectionModesOnNoisySynthCases) {
  // Default synth options: noise, holes, fragments, bumps. Both modes must stay close to the
  // truth; the numbers printed here are the ones in docs/TRANSFER.md.
  for (std::uint64_t seed : {11u, 12u}) {
    synth::SynthOptions o;
    o.seed = seed;
    o.pose = seed % 2 ? synth::PoseType::Standing : synth::PoseType::Supine;
    const synth::SynthCase c = synth::make_case(torso(), o);
    const fit::ScanTarget scan(c.scan);
    for (ProjectionMode mode : {ProjectionMode::ClosestPoint, ProjectionMode::AlongNormal}) {
      TransferOptions opt;
      opt.mode = mode;
      opt.fold_facing_down_cos = 1;  // the synthetic truth is the template's material curve, which the
                                     // fold slide deliberately leaves under a hanging breast
      const auto curves = transfer_drawings(torso(), true_fit(c), scan, opt);
      double sum = 0;
      for (const auto& tc : curves) {
        const Curve& truth = truth_curve(c, tc.name);
        const double d = curve_distance(tc.points, tc.closed, truth.points, truth.closed).mean_sym;
        sum += d;
        EXPECT_LT(d, 3.0) << tc.name << " seed " << seed;
      }
      std::printf("seed %llu %s: mean over curves %.3f mm\n", static_cast<unsigned long long>(seed),
                  mode == ProjectionMode::ClosestPoint ? "closest" : "normal ", sum / static_cast<double>(curves.size()));
    }
  }
}

TEST(DrawingTransfer, CurveOverAHoleIsFlaggedUnsupported) {
  const synth::SynthCase c = synth::make_case(torso(), clean_options(4));
  const Curve& truth = truth_curve(c, "breast_contour_R");
  const Vec3 centre = truth.points.row(truth.points.rows() / 3).transpose();
  const double radius = 15.0;
  TriangleMesh holed;
  holed.V = c.scan.V;
  std::vector<Index> keep;
  for (Index f = 0; f < c.scan.num_faces(); ++f) {
    bool inside = false;
    for (int k = 0; k < 3; ++k) inside = inside || (c.scan.V.row(c.scan.F(f, k)).transpose() - centre).norm() < radius;
    if (!inside) keep.push_back(f);
  }
  holed.F.resize(static_cast<Eigen::Index>(keep.size()), 3);
  for (size_t i = 0; i < keep.size(); ++i) holed.F.row(static_cast<Eigen::Index>(i)) = c.scan.F.row(keep[i]);
  ASSERT_LT(holed.num_faces(), c.scan.num_faces());

  const fit::ScanTarget scan(holed);
  for (ProjectionMode mode : {ProjectionMode::ClosestPoint, ProjectionMode::AlongNormal}) {
    TransferOptions opt;
    opt.mode = mode;
    const auto curves = transfer_drawings(torso(), true_fit(c), scan, opt);
    const TransferredCurve* contour = nullptr;
    for (const auto& tc : curves)
      if (tc.name == "breast_contour_R") contour = &tc;
    ASSERT_NE(contour, nullptr);
    int near_hole = 0, far = 0;
    for (Eigen::Index i = 0; i < contour->points.rows(); ++i) {
      const double d = (contour->points.row(i).transpose() - centre).norm();
      if (d < radius - 5.0) {
        ++near_hole;
        EXPECT_FALSE(contour->supported[static_cast<size_t>(i)]) << "point " << i << " at " << d << " mm from the hole centre";
      } else if (d > radius + 10.0) {
        ++far;
        EXPECT_TRUE(contour->supported[static_cast<size_t>(i)]) << "point " << i;
      }
    }
    EXPECT_GT(near_hole, 10);
    EXPECT_GT(far, 100);
    EXPECT_LT(contour->supported_fraction, 0.95);
    EXPECT_GT(contour->supported_fraction, 0.5);
    // where unsupported, the curve is the model's: still within a few mm of the truth
    EXPECT_LT(curve_distance(contour->points, true, truth.points, true).mean_sym, 3.0);
  }
}

TEST(DrawingTransfer, NothingWithinTheThresholdIsUnsupported) {
  const synth::SynthCase c = synth::make_case(torso(), clean_options(5));
  // Inflated by 15 mm along its normals the model is beyond the 10 mm threshold almost
  // everywhere; moved 1 m away, nothing is within it.
  const Points posed = true_fit(c);
  const fit::ScanTarget scan(c.scan);
  const Points inflated = posed + 15.0 * mesh::vertex_normals(posed, torso().rest.F);
  for (const auto& tc : transfer_drawings(torso(), inflated, scan)) {
    EXPECT_LT(tc.supported_fraction, 0.25) << tc.name;
    EXPECT_GT(tc.length_mm, 50.0) << tc.name;  // the model's curve is kept
  }
  Points far = posed;
  far.col(2).array() += 1000.0;
  const auto curves = transfer_drawings(torso(), far, scan);
  for (const auto& tc : curves) {
    EXPECT_EQ(tc.supported_fraction, 0.0) << tc.name;
    EXPECT_EQ(tc.mean_model_to_scan_mm, 0.0) << tc.name;
  }
}

TEST(DrawingTransfer, ValidatesOptionsAndInput) {
  TransferOptions o;
  o.max_distance_mm = 0;
  EXPECT_THROW(o.validate(), InvalidInput);
  o = {};
  o.smoothing_weight = 2;
  EXPECT_THROW(o.validate(), InvalidInput);
  o = {};
  o.fold_facing_down_cos = 0;
  EXPECT_THROW(o.validate(), InvalidInput);
  o = {};
  o.fold_max_slide_mm = -1;
  EXPECT_THROW(o.validate(), InvalidInput);
  const synth::SynthCase c = synth::make_case(torso(), clean_options(6));
  const fit::ScanTarget scan(c.scan);
  EXPECT_THROW(transfer_drawings(torso(), Points(3, 3), scan), InvalidInput);
  TriangleMesh fitted;
  fitted.V = true_fit(c);
  fitted.F = torso().rest.F;
  const DrawingTransfer t(scan, fitted);
  EXPECT_THROW(t.transfer("empty", false, Points(0, 3)), InvalidInput);
}

// A chest wall (y = 0, facing anterior −y) with a hanging "breast" on it, extruded along x: the
// profile (y, z) runs down the wall, out and down the breast's front, back along its flat
// underside (facing down) to the fold at (0, 40), and down the wall again.
TriangleMesh overhang_mesh() {
  const std::vector<Vec2> corners = {{0, 120}, {0, 90}, {-40, 70}, {-40, 40}, {0, 40}, {0, 0}};
  std::vector<Vec2> profile;
  for (size_t k = 0; k + 1 < corners.size(); ++k) {
    const int n = static_cast<int>(std::ceil((corners[k + 1] - corners[k]).norm() / 2.0));
    for (int s = 0; s < n; ++s) profile.push_back(corners[k] + (corners[k + 1] - corners[k]) * (double(s) / n));
  }
  profile.push_back(corners.back());
  const int nx = 51, nk = static_cast<int>(profile.size());
  TriangleMesh m;
  m.V.resize(nx * nk, 3);
  for (int i = 0; i < nx; ++i)
    for (int k = 0; k < nk; ++k) m.V.row(i * nk + k) = Vec3(-50 + 2.0 * i, profile[k].x(), profile[k].y()).transpose();
  m.F.resize(2 * (nx - 1) * (nk - 1), 3);
  Index f = 0;
  for (int i = 0; i + 1 < nx; ++i)
    for (int k = 0; k + 1 < nk; ++k) {
      const Index a = i * nk + k, b = (i + 1) * nk + k, c = i * nk + k + 1, d = (i + 1) * nk + k + 1;
      m.F.row(f++) << a, c, b;  // outward = anterior / down
      m.F.row(f++) << b, c, d;
    }
  return m;
}

TEST(DrawingTransfer, PointsUnderAHangingBreastSlideBackIntoTheFold) {
  const TriangleMesh m = overhang_mesh();
  const fit::ScanTarget scan(m);
  DrawingTransfer t(scan, m);
  const Vec3 underside(0, -30, 40), front(0, -40, 55), wall(0, 0, 20);
  // Without body axes, nothing moves.
  EXPECT_LT((t.slide_into_fold(underside) - underside).norm(), 1e-9);
  EXPECT_THROW(t.set_body_axes(Vec3(0, 0, 1), Vec3(0, -1, 0.5)), InvalidInput);
  t.set_body_axes(Vec3(0, 0, 1), Vec3(0, -1, 0));
  // On the underside (facing down): back along it to the fold, at the chest wall.
  const Vec3 slid = t.slide_into_fold(underside);
  EXPECT_GT(slid.y(), -3.0) << slid.transpose();
  EXPECT_NEAR(slid.z(), 40.0, 3.0) << slid.transpose();
  EXPECT_NEAR(slid.x(), 0.0, 1e-6);
  // Skin that does not face down stays.
  EXPECT_LT((t.slide_into_fold(front) - front).norm(), 1e-9);
  EXPECT_LT((t.slide_into_fold(wall) - wall).norm(), 1e-9);
  // The slide is bounded, and off when the threshold is 1.
  TransferOptions shorter;
  shorter.fold_max_slide_mm = 10;
  DrawingTransfer t10(scan, m, shorter);
  t10.set_body_axes(Vec3(0, 0, 1), Vec3(0, -1, 0));
  EXPECT_NEAR(t10.slide_into_fold(underside).y(), -20.0, 1.0);
  TransferOptions off;
  off.fold_facing_down_cos = 1;
  DrawingTransfer t_off(scan, m, off);
  t_off.set_body_axes(Vec3(0, 0, 1), Vec3(0, -1, 0));
  EXPECT_LT((t_off.slide_into_fold(underside) - underside).norm(), 1e-9);
  // A curve drawn along the underside ends up along the fold.
  Points line(21, 3);
  for (int i = 0; i < 21; ++i) line.row(i) = Vec3(-20 + 2.0 * i, -25, 40).transpose();
  const TransferredCurve c = t.transfer("imf", false, line);
  for (Eigen::Index i = 0; i < c.points.rows(); ++i) EXPECT_GT(c.points(i, 1), -3.0) << c.points.row(i);
}

TEST(DrawingTransfer, ToMarkupsKeepsNamesAndClosedness) {
  TransferredCurve a;
  a.name = "breast_contour_R";
  a.closed = true;
  a.points = Points::Random(5, 3);
  TransferredCurve b;
  b.name = "sternum";
  b.points = Points::Random(4, 3);
  const Markups m = to_markups({a, b});
  ASSERT_EQ(m.curves.size(), 2u);
  EXPECT_TRUE(m.curves[0].closed);
  EXPECT_FALSE(m.curves[1].closed);
  EXPECT_EQ(m.curves[1].name, "sternum");
  EXPECT_TRUE(m.curves[0].points == a.points);
}

}  // namespace
}  // namespace breastfit::transfer

// End to end on synthetic cases with the real registration: the transferred curves against the
// truth, for both projection modes and for the untransferred model curves (numbers in
// docs/TRANSFER.md).
#include "breastfit/pipeline/register_scan.h"

namespace breastfit::transfer {
namespace {

TEST(DrawingTransfer, AfterARealFitTransferIsNoWorseThanTheModelCurves) {
  double sum_model = 0, sum_closest = 0, sum_normal = 0;
  int n = 0;
  for (std::uint64_t seed : {21u, 22u, 23u, 24u}) {
    synth::SynthOptions o;
    o.seed = seed;
    o.pose = seed % 2 ? synth::PoseType::Standing : synth::PoseType::Supine;
    const synth::SynthCase c = synth::make_case(torso(), o);
    pipeline::RegisterRequest req;
    req.scan = c.scan;
    req.model = test::default_template();
    LandmarkSet lms;
    lms.points = c.input_landmarks;
    lms.declared_units = "mm";
    req.landmarks = lms;
    const pipeline::RegisterResult r = pipeline::register_scan(req);
    ASSERT_TRUE(r.usable());
    const fit::ScanTarget scan(r.scan.mesh_mm);
    std::printf("seed %llu (%s):", static_cast<unsigned long long>(seed), o.pose == synth::PoseType::Standing ? "standing" : "supine");
    for (ProjectionMode mode : {ProjectionMode::ClosestPoint, ProjectionMode::AlongNormal}) {
      TransferOptions opt;
      opt.mode = mode;
      opt.fold_facing_down_cos = 1;  // the synthetic truth is the template's material curve, which the
                                     // fold slide deliberately leaves under a hanging breast
      const auto curves = transfer_drawings(torso(), r.fit.vertices, scan, opt);
      for (const auto& tc : curves) {
        if (tc.name.rfind("breast_contour", 0) != 0 && tc.name != "sternum") continue;
        const Curve& truth = truth_curve(c, tc.name);
        const double d = curve_distance(tc.points, tc.closed, truth.points, truth.closed).mean_sym;
        (mode == ProjectionMode::ClosestPoint ? sum_closest : sum_normal) += d;
        if (mode == ProjectionMode::ClosestPoint) {
          // The template's drawing on the fitted model, before any projection onto the scan.
          const auto drawing_index = torso().drawing_index(tc.name);
          ASSERT_TRUE(drawing_index.has_value());
          const auto& drawing = torso().drawings[*drawing_index];
          Points model_points(static_cast<Index>(drawing.points.size()), 3);
          for (size_t k = 0; k < drawing.points.size(); ++k)
            model_points.row(k) = drawing.points[k].position(r.fit.vertices, torso().rest.F).transpose();
          const double dm = curve_distance(model_points, drawing.closed, truth.points, truth.closed).mean_sym;
          sum_model += dm;
          ++n;
          std::printf("  %s model %.2f closest %.2f", tc.name.c_str(), dm, d);
          EXPECT_LT(d, dm + 0.5) << tc.name << " seed " << seed;
        } else {
          std::printf(" normal %.2f", d);
        }
      }
    }
    std::printf("\n");
  }
  std::printf("mean over %d curves: model %.2f mm, closest point %.2f mm, along normal %.2f mm\n", n, sum_model / n,
              sum_closest / n, sum_normal / n);
  EXPECT_LT(sum_closest / n, sum_model / n);
}

}  // namespace
}  // namespace breastfit::transfer
