#include "breastfit/synth/synth_case.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/core/timer.h"
#include "breastfit/mesh/boundary.h"
#include "breastfit/mesh/landmark_names.h"
#include "breastfit/model/pose_evaluator.h"
#include "breastfit/spatial/closest_point_index.h"
#include "breastfit/template/default_template.h"
#include "support/toy_model.h"

namespace breastfit::synth {
namespace {

/// Options that fit the small toy torso (an elliptic cylinder 120 x 80 x 240 mm).
SynthOptions toy_options(std::uint64_t seed, PoseType pose = PoseType::Standing) {
  SynthOptions o;
  o.seed = seed;
  o.pose = pose;
  o.artifacts.hole_landmark_clearance_mm = 15.0;
  o.artifacts.hole_radius_mm = {6.0, 10.0};
  o.deformation.width_mm = {40.0, 60.0};
  return o;
}

const model::RiggedModel& toy() {
  static const model::RiggedModel m = test::make_toy_model();
  return m;
}

Vec3 to_file(const SynthCase& c, const Vec3& x_body) {
  const Mat3 R = c.T_body_to_scan_mm.topLeftCorner<3, 3>();
  const Vec3 t = c.T_body_to_scan_mm.topRightCorner<3, 1>();
  return c.scale_mm_to_file_units * (R * x_body + t);
}

TEST(SynthCase, IsDeterministic) {
  const SynthCase a = make_case(toy(), toy_options(5));
  const SynthCase b = make_case(toy(), toy_options(5));
  EXPECT_EQ(a.meta_json, b.meta_json);
  EXPECT_TRUE(a.scan.V == b.scan.V);
  EXPECT_TRUE(a.scan.F == b.scan.F);
  EXPECT_TRUE(a.truth_surface.V == b.truth_surface.V);
  const SynthCase c = make_case(toy(), toy_options(6));
  EXPECT_FALSE(a.scan.V.rows() == c.scan.V.rows() && a.scan.V == c.scan.V);
}

TEST(SynthCase, TruthLandmarksAndCurvesLieOnTheTruthSurface) {
  const SynthCase c = make_case(toy(), toy_options(7));
  ASSERT_EQ(c.truth_landmarks.size(), toy().landmarks.size());
  const spatial::ClosestPointIndex truth(c.truth_surface);
  for (const auto& l : c.truth_landmarks) EXPECT_LT(truth.closest(l.position).distance(), 1e-6) << l.name;
  ASSERT_EQ(c.truth_curves.size(), toy().drawings.size());
  for (size_t i = 0; i < c.truth_curves.size(); ++i) {
    const Curve& cv = c.truth_curves[i];
    EXPECT_EQ(cv.name, toy().drawings[i].name);
    EXPECT_EQ(cv.closed, toy().drawings[i].closed);
    ASSERT_GT(cv.points.rows(), 10);
    for (Index k = 0; k < cv.points.rows(); ++k) {
      EXPECT_LT(truth.closest(cv.points.row(k).transpose()).distance(), 1e-6);
      if (k > 0) {
        const double step = (cv.points.row(k) - cv.points.row(k - 1)).norm();
        EXPECT_GT(step, 0.7);
        EXPECT_LT(step, 1.3);
      }
    }
  }
}

TEST(SynthCase, ScanIsANoisyHoleyPartOfTheTruth) {
  const SynthOptions o = toy_options(8);
  const SynthCase c = make_case(toy(), o);
  const nlohmann::json meta = nlohmann::json::parse(c.meta_json);
  const Index body_vertices = meta["scan_stats"]["scan_body_vertices"].get<Index>();
  ASSERT_GT(body_vertices, 1000);
  EXPECT_LT(c.scan.num_faces(), c.truth_surface.num_faces());  // partial coverage
  const spatial::ClosestPointIndex truth(c.truth_surface);
  double worst = 0, sum = 0;
  for (Index v = 0; v < body_vertices; ++v) {
    const double d = truth.closest(c.scan.V.row(v).transpose()).distance();
    worst = std::max(worst, d);
    sum += d;
  }
  const double noise = o.artifacts.white_noise_mm + o.artifacts.lowfreq_noise_mm;
  EXPECT_LT(sum / body_vertices, noise);
  EXPECT_LT(worst, 6.0 * noise);
  // Fragments float off the surface.
  double frag_far = 0;
  for (Index v = body_vertices; v < c.scan.num_vertices(); ++v)
    frag_far = std::max(frag_far, truth.closest(c.scan.V.row(v).transpose()).distance());
  EXPECT_GT(frag_far, o.artifacts.fragment_distance_mm.lo - 5.0);
  // Holes: more border loops than the cut/coverage outline alone.
  EXPECT_GT(mesh::boundary_loops(c.scan).size(), 1u);
  EXPECT_EQ(meta["scan_stats"]["holes"].size(), static_cast<size_t>(o.artifacts.n_holes));
}

TEST(SynthCase, InputLandmarksAreSnappedToTheScan) {
  const SynthOptions o = toy_options(9);
  const SynthCase c = make_case(toy(), o);
  const nlohmann::json meta = nlohmann::json::parse(c.meta_json);
  TriangleMesh body;
  const Index nv = meta["scan_stats"]["scan_body_vertices"].get<Index>();
  const Index nf = meta["scan_stats"]["scan_body_faces"].get<Index>();
  body.V = c.scan.V.topRows(nv);
  body.F = c.scan.F.topRows(nf);
  const spatial::ClosestPointIndex scan(body);
  ASSERT_EQ(c.input_landmarks.size(), c.truth_landmarks.size());
  double total = 0;
  for (size_t i = 0; i < c.input_landmarks.size(); ++i) {
    EXPECT_EQ(c.input_landmarks[i].name, c.truth_landmarks[i].name);
    EXPECT_LT(scan.closest(c.input_landmarks[i].position).distance(), 1e-6);
    const double err = (c.input_landmarks[i].position - c.truth_landmarks[i].position).norm();
    EXPECT_LT(err, 6.0 * o.landmark_noise_mm + 3.0);
    EXPECT_NEAR(err, c.input_landmark_errors[i].error_vs_truth_mm, 1e-9);
    total += err;
  }
  EXPECT_GT(total, 0.0);  // annotated, not copied
}

TEST(SynthCase, TransformMapsTheBodyFrameToTheScanFrame) {
  for (const std::string units : {"mm", "m"}) {
    SynthOptions o = toy_options(10, PoseType::Supine);
    o.units = units;
    const SynthCase c = make_case(toy(), o);
    EXPECT_EQ(c.units, units);
    EXPECT_DOUBLE_EQ(c.scale_mm_to_file_units, units == "m" ? 1e-3 : 1.0);
    const Mat3 R = c.T_body_to_scan_mm.topLeftCorner<3, 3>();
    EXPECT_LT((R * R.transpose() - Mat3::Identity()).norm(), 1e-12);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
    for (size_t i = 0; i < c.truth_landmarks.size(); ++i)
      EXPECT_LT((to_file(c, c.truth_landmarks_body[i].position) - c.truth_landmarks[i].position).norm(),
                1e-9 * (units == "m" ? 1e-3 : 1.0) + 1e-12);
    // The meta.json transform is the same.
    const nlohmann::json meta = nlohmann::json::parse(c.meta_json);
    for (int r = 0; r < 4; ++r)
      for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(meta["T_body_to_scan_mm"][r][k].get<double>(), c.T_body_to_scan_mm(r, k));
    EXPECT_EQ(meta["units"], units);
    EXPECT_DOUBLE_EQ(meta["scale_mm_to_file_units"].get<double>(), c.scale_mm_to_file_units);
    // Supine base orientation (before the misalignment) has the scanner Y axis anterior.
    const double max_rot = o.misalign_rotation_deg * std::numbers::pi / 180.0;
    const Vec3 anterior_in_scan = R * Vec3(0, -1, 0);
    EXPECT_GT(anterior_in_scan.y(), std::cos(max_rot) - 1e-9);
  }
  // Same seed in mm and m: identical geometry up to the factor 1000.
  SynthOptions mm = toy_options(11), m = toy_options(11);
  m.units = "m";
  const SynthCase a = make_case(toy(), mm), b = make_case(toy(), m);
  ASSERT_EQ(a.scan.V.rows(), b.scan.V.rows());
  EXPECT_LT((a.scan.V - 1000.0 * b.scan.V).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(SynthCase, TrueParametersReproduceTheTruthUpToTheSmoothDeformation) {
  SynthOptions o = toy_options(12);
  o.deformation.n_bumps = 0;
  o.refinement.loop = false;  // midpoint refinement: the truth is exactly the posed model
  const SynthCase c = make_case(toy(), o);
  model::PoseEvaluator ev(toy());
  ev.set_params(c.true_params_scan);
  for (size_t i = 0; i < toy().landmarks.size(); ++i) {
    const Vec3 p = ev.surface_point(toy().landmarks[i].point);
    EXPECT_LT((p - c.truth_landmarks[i].position).norm(), 1e-6) << toy().landmarks[i].name;
  }
  // With the deformation the truth departs from the model by at most the bump amplitudes.
  SynthOptions od = toy_options(12);
  od.refinement.loop = false;
  const SynthCase d = make_case(toy(), od);
  double worst = 0;
  for (size_t i = 0; i < toy().landmarks.size(); ++i)
    worst = std::max(worst, (ev.surface_point(toy().landmarks[i].point) - d.truth_landmarks[i].position).norm());
  EXPECT_GT(worst, 1e-3);
  EXPECT_LT(worst, od.deformation.n_bumps * od.deformation.amplitude_mm.hi);
}

TEST(SynthCase, RejectsInvalidOptions) {
  SynthOptions o = toy_options(1);
  o.units = "inch";
  EXPECT_THROW(make_case(toy(), o), InvalidInput);
}

TEST(SynthCase, DefaultTemplateCaseLooksLikeTheBench) {
  const model::RiggedModel model = templ::build_default_template();
  for (PoseType pose : {PoseType::Standing, PoseType::Supine}) {
    SynthOptions o;
    o.seed = 21;
    o.pose = pose;
    Timer timer;
    const SynthCase c = make_case(model, o);
    const double seconds = timer.seconds();
    EXPECT_LT(seconds, 20.0);  // ~1-3 s on an idle machine; generous for loaded CI
    EXPECT_EQ(c.truth_landmarks.size(), kLandmarkNames.size());
    for (const char* name : {"breast_contour_R", "breast_contour_L", "sternum"}) {
      bool found = false;
      for (const auto& cv : c.truth_curves) found = found || cv.name == name;
      EXPECT_TRUE(found) << name;
    }
    EXPECT_GT(c.scan.num_faces(), 50000);
    EXPECT_LT(c.scan.num_faces(), 400000);
    const nlohmann::json meta = nlohmann::json::parse(c.meta_json);
    const double observed = meta["scan_stats"]["observed_area_fraction"].get<double>();
    EXPECT_GT(observed, 0.4);
    EXPECT_LT(observed, 0.98);
    EXPECT_LT(meta["scan_stats"]["dense_edge_mm_median"].get<double>(), 3.0);
    if (pose == PoseType::Supine) {
      EXPECT_GT(meta["pose"]["arms"]["R"]["abduction_deg"].get<double>(), 60.0);
      EXPECT_FALSE(meta["pose"]["supine_shapes"].empty());
    }
  }
}

}  // namespace
}  // namespace breastfit::synth
