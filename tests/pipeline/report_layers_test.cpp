// The report's overlay figures' scan layers (drawn before the fit ends): set up from the
// template as the landmark initialisation places it, none without landmarks, the same figures
// whether drawn ahead by the drawing thread, taken by the figures, or drawn after the fit (one
// thread or several), the plan's errors, the crop, and the legend clear of the body.
#include "breastfit/pipeline/report_layers.h"

#include <algorithm>
#include <future>

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"
#include "breastfit/fit/parallel_chunks.h"
#include "breastfit/fit/registration.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/render/torso_overlays.h"
#include "breastfit/synth/synth_case.h"
#include "pipeline/report_test_case.h"
#include "support/scoped_env.h"

namespace breastfit {
namespace {

pipeline::ReportFigureOptions small_options() {
  pipeline::ReportFigureOptions o;
  o.size = 320;
  o.side_size = 200;
  return o;
}

void expect_same_pngs(const pipeline::ReportFigures& a, const pipeline::ReportFigures& b) {
  ASSERT_EQ(a.figures.size(), b.figures.size());
  for (size_t i = 0; i < a.figures.size(); ++i) EXPECT_EQ(a.figures[i].png, b.figures[i].png) << a.figures[i].id;
  EXPECT_EQ(a.body_frame, b.body_frame);
}

TEST(ReportLayers, SetUpFromTheTemplateAsTheLandmarkInitialisationPlacesIt) {
  const auto& r = test::report_test_result();
  const auto& model = test::report_test_model();
  ASSERT_GE(r.initial_landmarks.size(), 3u);
  const auto layers = pipeline::plan_report_layers(r, model, small_options());
  ASSERT_TRUE(layers);
  EXPECT_NE(layers->frame.description.find("landmarks"), std::string::npos) << layers->frame.description;
  ASSERT_EQ(layers->scan_scene.meshes.size(), 1u);
  const TriangleMesh& scan = layers->scan_scene.meshes[0].mesh;
  EXPECT_TRUE(scan.has_normals());
  EXPECT_GT(scan.num_faces(), r.scan.mesh_mm.num_faces() * 9 / 10);  // the synthetic scan is all torso
  // The legend's band: every drawing's name and the off-scan entry, no points.
  ASSERT_EQ(layers->scan_scene.polylines.size(), model.drawings.size() + 2);
  for (size_t k = 0; k < model.drawings.size(); ++k) EXPECT_EQ(layers->scan_scene.polylines[k].name, model.drawings[k].name);
  EXPECT_EQ(layers->scan_scene.polylines[model.drawings.size()].name, pipeline::kOffScanLegend);
  EXPECT_EQ(layers->scan_scene.polylines.back().name, render::kPlacedLandmarkLegend);
  for (const auto& l : layers->scan_scene.polylines) EXPECT_EQ(l.points.rows(), 0);
  // The views' frame is close to the one of the fitted model (the fit moves the body little).
  const Eigen::Matrix3d fitted = pipeline::render_report_figures(r, small_options()).body_to_world.topLeftCorner<3, 3>();
  const Eigen::Matrix3d initial = layers->frame.body_to_world.topLeftCorner<3, 3>();
  const double angle_deg = Eigen::AngleAxisd(fitted.transpose() * initial).angle() * 180 / 3.14159265358979;
  EXPECT_LT(angle_deg, 10.0);
}

TEST(ReportLayers, NoneWithoutALandmarkInitialisation) {
  const auto& r = test::report_test_result();
  const auto& model = test::report_test_model();
  std::vector<fit::LandmarkTarget> two(r.initial_landmarks.begin(), r.initial_landmarks.begin() + 2);
  EXPECT_FALSE(pipeline::plan_report_layers(r.scan.mesh_mm, model, two, small_options()));
  // The report's figures are then framed from the fitted model, as render_report_figures does.
  pipeline::RegisterResult landmark_free = r;
  landmark_free.initial_landmarks.clear();
  expect_same_pngs(pipeline::report_figures(landmark_free, model, small_options()),
                   pipeline::render_report_figures(landmark_free, small_options()));
}

TEST(ReportLayers, DrawnAheadOrAfterwardsTheSameFigures) {
  const auto& r = test::report_test_result();
  const auto& model = test::report_test_model();
  const pipeline::ReportFigures after = pipeline::report_figures(r, model, small_options());
  auto planned = pipeline::plan_report_layers(r, model, small_options());
  ASSERT_TRUE(planned);
  expect_same_pngs(pipeline::render_report_figures(r, *planned, small_options()), after);
  // Every layer drawn by the drawing thread before the figures take them.
  auto ahead = std::make_shared<pipeline::ReportLayerDrawing>(
      [&] { return pipeline::plan_report_layers(r, model, small_options()); }, small_options());
  ahead->wait();
  expect_same_pngs(pipeline::report_figures(r, model, small_options(), ahead), after);
  // Taken by the figures while the thread draws (on one thread or several).
  for (bool parallel : {false, true}) {
    pipeline::ReportFigureOptions o = small_options();
    o.parallel = parallel;
    auto racing = std::make_shared<pipeline::ReportLayerDrawing>(
        [&] { return pipeline::plan_report_layers(r, model, o); }, o);
    expect_same_pngs(pipeline::report_figures(r, model, o, racing), after);
  }
  // Other sizes than the layers': refused.
  pipeline::ReportFigureOptions bigger = small_options();
  bigger.size += 16;
  auto other = std::make_shared<pipeline::ReportLayerDrawing>(
      [&] { return pipeline::plan_report_layers(r, model, small_options()); }, small_options());
  EXPECT_THROW(pipeline::report_figures(r, model, bigger, other), InvalidInput);
  // The landmark-free way differs only by the frame and crop (same sizes and ids).
  const pipeline::ReportFigures fitted = pipeline::render_report_figures(r, small_options());
  for (size_t i = 0; i < after.figures.size(); ++i) {
    EXPECT_EQ(after.figures[i].image.width(), fitted.figures[i].image.width());
    EXPECT_EQ(after.figures[i].id, fitted.figures[i].id);
  }
}

TEST(ReportLayers, AnErrorOfThePlanComesFromLayers) {
  pipeline::ReportLayerDrawing failing([]() -> std::optional<pipeline::ReportLayers> { throw InvalidInput("bad"); },
                                       small_options());
  EXPECT_THROW(failing.layers(), InvalidInput);
  pipeline::ReportLayerDrawing none([] { return std::optional<pipeline::ReportLayers>(); }, small_options());
  EXPECT_EQ(none.layers(), nullptr);
}

TEST(ReportLayers, StartedBesideTheFitGiveTheReportsFigures) {
  const auto& model = test::report_test_model();
  synth::SynthOptions so;
  so.seed = 11;
  so.pose = synth::PoseType::Supine;
  pipeline::RegisterRequest req = test::synth_request(synth::make_case(model, so));
  const std::optional<LandmarkSet> lms = req.landmarks;
  pipeline::PreparedTarget target = pipeline::prepare_target(req.scan, req.scan_name, {}, req.options);
  auto started = pipeline::start_report_layers(req, target, small_options());
  const pipeline::RegisterResult r = pipeline::register_prepared(req, target);
  ASSERT_NE(started->layers(), nullptr);
  expect_same_pngs(pipeline::report_figures(r, model, small_options(), started),
                   pipeline::report_figures(r, model, small_options()));

  // Without landmarks nothing is drawn ahead; the figures are framed from the fitted model.
  req.landmarks.reset();
  EXPECT_EQ(pipeline::start_report_layers(req, target, small_options())->layers(), nullptr);
  req.landmarks = lms;
  req.options.use_landmarks = false;
  auto none = pipeline::start_report_layers(req, target, small_options());
  EXPECT_EQ(none->layers(), nullptr);
  expect_same_pngs(pipeline::report_figures(r, model, small_options(), none),
                   pipeline::render_report_figures(r, small_options()));
}

TEST(ReportLayers, StartedBeforeTheIndexWhileTheTemplateLoadsTheSameFigures) {
  const auto& model = test::report_test_model();
  synth::SynthOptions so;
  so.seed = 12;
  pipeline::RegisterRequest req = test::synth_request(synth::make_case(model, so));
  // As `register` starts them: from the prepared scan, before the index is built, the template
  // still loading (here: given only after the index is built).
  std::promise<std::shared_ptr<const model::RiggedModel>> loading;
  std::shared_future<std::shared_ptr<const model::RiggedModel>> loaded = loading.get_future().share();
  std::shared_ptr<pipeline::ReportLayerDrawing> early;
  bool seen_before_index = false;
  pipeline::PreparedTarget target =
      pipeline::prepare_target(req.scan, req.scan_name, {}, req.options, [&](const pipeline::PreparedScan& scan) {
        seen_before_index = true;
        EXPECT_EQ(scan.mesh_mm.num_faces(), req.scan.num_faces());
        early = pipeline::start_report_layers(scan, req.landmarks, req.options, [loaded] { return loaded.get(); },
                                              small_options());
      });
  ASSERT_TRUE(seen_before_index);
  loading.set_value(req.model);
  auto after_index = pipeline::start_report_layers(req, target, small_options());
  const pipeline::RegisterResult r = pipeline::register_prepared(req, target);
  ASSERT_NE(early->layers(), nullptr);
  const pipeline::ReportFigures after = pipeline::report_figures(r, model, small_options());
  expect_same_pngs(pipeline::report_figures(r, model, small_options(), early), after);
  expect_same_pngs(pipeline::report_figures(r, model, small_options(), after_index), after);

  // The template's error comes from layers(); a landmark-free fit starts nothing.
  auto failing = pipeline::start_report_layers(
      target.scan, req.landmarks, req.options,
      []() -> std::shared_ptr<const model::RiggedModel> { throw IoError("torso.glb", "cannot read"); }, small_options());
  EXPECT_THROW(failing->layers(), IoError);
  EXPECT_EQ(pipeline::start_report_layers(target.scan, std::nullopt, req.options, [] { return test::default_template(); },
                                          small_options())
                ->layers(),
            nullptr);
}

TEST(ReportLayers, TheCropLeavesOutFarFragments) {
  const auto& r = test::report_test_result();
  const auto& model = test::report_test_model();
  TriangleMesh scan = r.scan.mesh_mm;
  // A table-sized triangle 1.5 m from the body's centre.
  const Eigen::Index n = scan.V.rows();
  const Vec3 far = scan.V.colwise().mean().transpose() + Vec3(0, 0, 1500);
  scan.V.conservativeResize(n + 3, 3);
  scan.V.row(n) = far.transpose();
  scan.V.row(n + 1) = (far + Vec3(300, 0, 0)).transpose();
  scan.V.row(n + 2) = (far + Vec3(0, 300, 0)).transpose();
  scan.F.conservativeResize(scan.F.rows() + 1, 3);
  scan.F.row(scan.F.rows() - 1) << static_cast<int>(n), static_cast<int>(n + 1), static_cast<int>(n + 2);
  const auto layers = pipeline::plan_report_layers(scan, model, r.initial_landmarks, small_options());
  ASSERT_TRUE(layers);
  const TriangleMesh& kept = layers->scan_scene.meshes[0].mesh;
  EXPECT_LT(kept.num_faces(), scan.num_faces());
  for (Eigen::Index i = 0; i < kept.V.rows(); ++i) EXPECT_GT((kept.V.row(i).transpose() - far).norm(), 200.0);
}

TEST(ReportLayers, TheLegendNeverCoversTheBody) {
  // Every overlay figure: the legend's box (of the figure's real overlays) holds only background
  // in the layer of the scan alone.
  const auto& r = test::report_test_result();
  pipeline::ReportFigureOptions o = small_options();
  o.supersample = 1;
  auto layers = pipeline::plan_report_layers(r, test::report_test_model(), o);
  ASSERT_TRUE(layers);
  for (size_t k = 0; k < pipeline::kOverlayFigures; ++k) {
    const render::RenderOptions ro = pipeline::overlay_render_options(k, o, layers->frame.body_to_world);
    const render::Image scan_alone = pipeline::draw_report_layer(*layers, k, o).resolve();
    pipeline::ReportFigureOptions sized = o;
    if (pipeline::overlay_figure_specs()[k].small) sized.size = o.side_size;
    const auto box = render::legend_box(pipeline::overlay_scene(r, sized), ro);
    ASSERT_TRUE(box) << k;
    // Within the band the framing kept clear (every entry the figures can have).
    const auto band = render::legend_box(layers->scan_scene, ro);
    ASSERT_TRUE(band) << k;
    EXPECT_GE(box->min().y(), band->min().y()) << k;
    int body = 0;
    for (int y = std::max(0, box->min().y()); y < std::min(ro.height, box->max().y()); ++y)
      for (int x = std::max(0, box->min().x()); x < std::min(ro.width, box->max().x()); ++x)
        body += !(scan_alone.at(x, y) == ro.background);
    EXPECT_EQ(body, 0) << pipeline::overlay_figure_specs()[k].id;
  }
}

TEST(ReportLayers, DrawnBesideAFitFromThreeLandmarksWhoseAutomaticThreadsLeaveThemACore) {
  LandmarkSet three;
  three.points = {{"sternal_notch", Vec3(0, 0, 0)}, {"nipple_R", Vec3(-90, -200, 60)}, {"nipple_L", Vec3(90, -200, 60)}};
  LandmarkSet two = three;
  two.points.pop_back();
  fit::FitOptions o;
  EXPECT_TRUE(pipeline::layers_drawn_beside_fit(three, o));
  EXPECT_FALSE(pipeline::layers_drawn_beside_fit(std::nullopt, o));
  EXPECT_FALSE(pipeline::layers_drawn_beside_fit(two, o));
  fit::FitOptions landmark_free = o;
  landmark_free.use_landmarks = false;
  EXPECT_FALSE(pipeline::layers_drawn_beside_fit(three, landmark_free));
  fit::FitOptions first_two = o, first_three = o;
  first_two.max_landmarks = 2;
  first_three.max_landmarks = 3;
  EXPECT_FALSE(pipeline::layers_drawn_beside_fit(three, first_two));
  EXPECT_TRUE(pipeline::layers_drawn_beside_fit(three, first_three));

  {
    const test::ScopedEnv no_omp("OMP_NUM_THREADS", nullptr);
    // The automatic count, one core fewer (the load average may move between the two reads).
    const int before = fit::resolve_threads(0);
    const int beside = pipeline::fit_threads_beside_layers(three, o);
    const int after = fit::resolve_threads(0);
    EXPECT_TRUE(beside == std::max(1, before - 1) || beside == std::max(1, after - 1)) << beside;
    EXPECT_EQ(pipeline::fit_threads_beside_layers(two, o), 0);  // no layers beside the fit: as set
    EXPECT_EQ(pipeline::fit_threads_beside_layers(three, landmark_free), 0);
    fit::FitOptions two_threads = o;
    two_threads.threads = 2;
    EXPECT_EQ(pipeline::fit_threads_beside_layers(three, two_threads), 2);  // a person's count is kept
  }
  const test::ScopedEnv omp("OMP_NUM_THREADS", "2");
  EXPECT_EQ(pipeline::fit_threads_beside_layers(three, o), 0);  // the environment's count is kept
}

}  // namespace
}  // namespace breastfit
