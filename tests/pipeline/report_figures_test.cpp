// The report's figures on a real registration of a synthetic case: sizes, what each shows
// (drawing colours, landmark red, placed landmarks, colour map and its adaptive scale), the
// legend clear of the body, the one drawing palette shared with `render` and scan_painted.ply,
// the distances behind the distance figure, off-scan parts of a drawing, determinism, options.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/pipeline/report_figures.h"
#include "breastfit/render/colormap.h"
#include "breastfit/render/torso_overlays.h"
#include "breastfit/transfer/drawing_outputs.h"
#include "pipeline/report_test_case.h"

namespace breastfit {
namespace {

using pipeline::ReportFigureOptions;

bool near(render::Rgb a, render::Rgb b, int tol) {
  return std::abs(a.r - b.r) <= tol && std::abs(a.g - b.g) <= tol && std::abs(a.b - b.b) <= tol;
}

int count_near(const render::Image& img, render::Rgb c, int tol) {
  int n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) n += near(img.at(x, y), c, tol);
  return n;
}

/// Pixels of the landmark discs' red (shaded discs: any strong, dark-green-and-blue red).
int count_red(const render::Image& img) {
  int n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const render::Rgb c = img.at(x, y);
      n += c.r > 120 && c.g < 70 && c.b < 70;
    }
  return n;
}

ReportFigureOptions small_options() {
  ReportFigureOptions o;
  o.size = 400;
  o.side_size = 240;
  return o;
}

const pipeline::ReportFigures& small_figures() {
  static const pipeline::ReportFigures f = [] {
    return pipeline::render_report_figures(test::report_test_result(), small_options());
  }();
  return f;
}

TEST(ReportFigures, SixSquareFiguresFrontObliquesSidesDistance) {
  const auto& figs = small_figures().figures;
  ASSERT_EQ(figs.size(), 6u);
  const char* ids[] = {"front", "oblique-right", "oblique-left", "side-right", "side-left", "distance"};
  for (size_t i = 0; i < figs.size(); ++i) {
    const auto& f = figs[i];
    EXPECT_EQ(f.id, ids[i]);
    const int size = f.id == "front" || f.id == "distance" ? 400 : 240;  // the side views at the size shown
    EXPECT_EQ(f.image.width(), size) << f.id;
    EXPECT_EQ(f.image.height(), size) << f.id;
    EXPECT_FALSE(f.title.empty());
    EXPECT_FALSE(f.caption.empty());
  }
  EXPECT_NE(small_figures().body_frame.find("landmarks"), std::string::npos) << small_figures().body_frame;
}

TEST(ReportFigures, OverlayFiguresShowEveryDrawingAndTheLandmarks) {
  const auto& r = test::report_test_result();
  for (int k = 0; k < 5; ++k) {
    const render::Image& img = small_figures().figures[k].image;
    // Every drawing's colour appears (its line and its legend swatch).
    for (size_t c = 0; c < r.drawings_on_scan.size(); ++c)
      EXPECT_GT(count_near(img, pipeline::report_curve_colour(r.drawings_on_scan[c].name, c), 12), k == 0 ? 20 : 8)
          << "figure " << k << " curve " << r.drawings_on_scan[c].name;
    EXPECT_GT(count_red(img), k == 0 ? 40 : 10) << "figure " << k;
  }
}

TEST(ReportFigures, PlacedLandmarksAreDrawnDarkAndJoinedToTheFittedOnes) {
  const auto& r = test::report_test_result();
  ASSERT_FALSE(r.fit.landmarks.empty());
  const render::Scene scene = pipeline::overlay_scene(r);
  int placed = 0, joins = 0, legend = 0;
  for (const auto& p : scene.points) placed += p.colour == render::kPlacedLandmarkColour;
  for (const auto& l : scene.polylines) {
    if (l.colour != render::kPlacedLandmarkColour) continue;
    if (l.points.rows() == 0) {
      ++legend;
      continue;
    }
    ++joins;
    ASSERT_EQ(l.points.rows(), 2);
    // From a placed landmark to the fitted landmark of the same name.
    bool found = false;
    for (const auto& t : r.fit.landmarks)
      if (t.position.isApprox(l.points.row(0).transpose())) {
        const NamedPoint* f = r.model_landmarks_mm.find_point(t.name);
        ASSERT_NE(f, nullptr);
        EXPECT_TRUE(f->position.isApprox(l.points.row(1).transpose())) << t.name;
        found = true;
      }
    EXPECT_TRUE(found);
  }
  EXPECT_EQ(placed, static_cast<int>(r.fit.landmarks.size()));
  EXPECT_EQ(joins, static_cast<int>(r.fit.landmarks.size()));
  EXPECT_EQ(legend, 1);
  // And they show in the front figure: near-black disc pixels.
  EXPECT_GT(count_near(small_figures().figures[0].image, render::kPlacedLandmarkColour, 30), 20);
}

TEST(ReportFigures, OnePaletteForTheFiguresRenderAndScanPainted) {
  // The drawing colours of report.html (figures, swatches; the workstation gets the same), of
  // `breastfit render` (add_curve) and of scan_painted.ply / drawings.ply agree, by kind and for
  // other drawings by index.
  const std::vector<std::string> names = {"breast_contour_R", "breast_contour_L", "imf_R", "imf_L", "sternum",
                                          "incision_a", "incision_b", "incision_c"};
  render::Scene scene;
  Points P(2, 3);
  P << 0, 0, 0, 1, 0, 0;
  for (size_t k = 0; k < names.size(); ++k) {
    render::add_curve(scene, names[k], false, P, render::OverlaySizes(512));
    const render::Rgb report = pipeline::report_curve_colour(names[k], k);
    const transfer::Rgb painted = transfer::drawing_color(names[k], k);
    EXPECT_EQ(scene.polylines[k].colour, report) << names[k];
    EXPECT_EQ((render::Rgb{painted[0], painted[1], painted[2]}), report) << names[k];
  }
  // The sternum is magenta everywhere (it was green in render and red in scan_painted.ply).
  EXPECT_EQ(pipeline::report_curve_colour("sternum", 1), (render::Rgb{200, 30, 130}));
}

TEST(ReportFigures, TheLegendNeverCoversTheBody) {
  // Every overlay figure: the legend's box holds only background in the same view rendered
  // without legend, labels and letters (the body's silhouette).
  const auto& r = test::report_test_result();
  const pipeline::ReportFigureOptions o = small_options();
  const render::Scene scene = pipeline::overlay_scene(r, o);
  const Eigen::Matrix4d body_to_world = small_figures().body_to_world;
  for (render::View v : render::default_views()) {
    render::RenderOptions ro;
    ro.width = ro.height = o.size;
    ro.supersample = 1;
    ro.text_scale = o.text_scale;
    ro.margin = 0.04;
    ro.view = v;
    ro.body_to_world = body_to_world;
    ro.title = "Front: scan, landmarks, drawings";
    const auto box = render::legend_box(scene, ro);
    ASSERT_TRUE(box) << render::view_name(v);
    render::RenderOptions bare = ro;
    bare.camera = render::scene_camera(scene, ro);
    bare.show_legend = bare.show_labels = bare.show_orientation = false;
    bare.title.clear();
    const render::Image silhouette = render::render_scene(scene, bare);
    int body = 0;
    for (int y = std::max(0, box->min().y()); y < std::min(o.size, box->max().y()); ++y)
      for (int x = std::max(0, box->min().x()); x < std::min(o.size, box->max().x()); ++x)
        body += !(silhouette.at(x, y) == ro.background);
    EXPECT_EQ(body, 0) << render::view_name(v);
    // The legend is really there in the figure.
    const render::Image with = render::render_scene(scene, ro);
    int legend_px = 0;
    for (int y = box->min().y(); y < box->max().y(); ++y)
      for (int x = box->min().x(); x < box->max().x(); ++x) legend_px += !(with.at(x, y) == ro.background);
    EXPECT_GT(legend_px, 100) << render::view_name(v);
  }
}

TEST(ReportFigures, DistanceFigureScaleAdaptsToTheDistances) {
  const auto& f = small_figures();
  const render::Image& img = f.figures.back().image;
  const double hi = f.distance_scale_mm;
  EXPECT_EQ(hi, pipeline::distance_scale_mm(f.distances_mm));
  char top[32];
  std::snprintf(top, sizeof top, "0 to %g mm", hi);
  EXPECT_NE(f.figures.back().caption.find(top), std::string::npos) << f.figures.back().caption;
  // The colour bar spans 0..hi: its two end colours are present.
  EXPECT_GE(count_near(img, render::colormap(render::Colormap::Viridis, 0.0, 0.0, hi), 3), 5);
  EXPECT_GE(count_near(img, render::colormap(render::Colormap::Viridis, hi, 0.0, hi), 3), 5);
  // Not almost one colour: the model's pixels spread over the map (dark, middle and bright).
  int dark = 0, middle = 0, bright = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const render::Rgb c = img.at(x, y);
      dark += near(c, render::colormap(render::Colormap::Viridis, 0.15, 0, 1), 40);
      middle += near(c, render::colormap(render::Colormap::Viridis, 0.5, 0, 1), 40);
      bright += near(c, render::colormap(render::Colormap::Viridis, 0.85, 0, 1), 40);
    }
  EXPECT_GT(dark, 500);
  EXPECT_GT(middle, 500);
  EXPECT_GT(bright, 100);
  // No landmark red: the distance figure is the colour map alone.
  EXPECT_EQ(count_red(img), 0);
  // A fixed range when asked.
  ReportFigureOptions o = small_options();
  o.distance_range_mm = 10.0;
  o.parallel = false;
  EXPECT_EQ(pipeline::render_report_figures(test::report_test_result(), o).distance_scale_mm, 10.0);
}

TEST(ReportFigures, DistanceScaleIsThe95thPercentileRoundedUpToANiceNumber) {
  auto scale = [](std::vector<double> v) {
    return pipeline::distance_scale_mm(Eigen::Map<Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())));
  };
  std::vector<double> d(100);
  for (int i = 0; i < 100; ++i) d[i] = 0.037 * (i + 1);  // 95th percentile 3.515
  EXPECT_EQ(scale(d), 4.0);
  for (double& x : d) x *= 10;  // 35.15
  EXPECT_EQ(scale(d), 40.0);
  d.push_back(std::numeric_limits<double>::quiet_NaN());  // NaN (no scan) ignored
  d.push_back(1e6);                                       // one outlier does not move it
  EXPECT_EQ(scale(d), 40.0);
  EXPECT_EQ(scale({2.4, 2.5, 2.5}), 2.5);
  EXPECT_EQ(scale({0.1, 0.2}), pipeline::kMinDistanceScaleMm);  // never below 1 mm
  EXPECT_EQ(scale({}), pipeline::kMinDistanceScaleMm);
  EXPECT_EQ(scale({8.5}), 10.0);
  EXPECT_EQ(scale({14.0}), 15.0);
}

TEST(ReportFigures, DistancesAreThoseOfTheSurfaceError) {
  const auto& r = test::report_test_result();
  const Eigen::VectorXd d = pipeline::model_to_scan_distances(r);
  ASSERT_EQ(d.size(), r.fitted_mm.V.rows());
  int n = 0;
  double sum = 0, mx = 0;
  for (Eigen::Index i = 0; i < d.size(); ++i)
    if (std::isfinite(d[i])) {
      ++n;
      sum += d[i];
      mx = std::max(mx, d[i]);
    }
  EXPECT_EQ(n, r.surface.n);
  EXPECT_NEAR(sum / n, r.surface.mae, 1e-9);
  EXPECT_NEAR(mx, r.surface.max, 1e-9);
  EXPECT_LT(n, d.size());  // the synthetic scan has holes and a cropped border: some vertices are not compared
}

TEST(ReportFigures, OffScanPartsOfADrawingArePaleAndLabelledOnce) {
  pipeline::RegisterResult r = test::report_test_result();
  ASSERT_FALSE(r.drawings_on_scan.empty());
  r.fit.landmarks.clear();  // the drawings alone (the placed landmarks' joins: their own test)
  for (auto& other : r.drawings_on_scan) other.supported.assign(static_cast<size_t>(other.points.rows()), true);
  // With every curve on the scan: one polyline per curve (closed ones closed), no legend-only entry.
  const render::Scene all_on = pipeline::overlay_scene(r);
  ASSERT_EQ(all_on.polylines.size(), r.drawings_on_scan.size());
  for (size_t k = 0; k < r.drawings_on_scan.size(); ++k) {
    EXPECT_EQ(all_on.polylines[k].name, r.drawings_on_scan[k].name);
    EXPECT_EQ(all_on.polylines[k].closed, r.drawings_on_scan[k].closed);
    EXPECT_EQ(all_on.polylines[k].colour, pipeline::report_curve_colour(r.drawings_on_scan[k].name, k));
  }
  // The first quarter of the first (closed) curve off the scan.
  auto& c = r.drawings_on_scan[0];
  ASSERT_TRUE(c.closed) << c.name;
  const render::Rgb colour = pipeline::report_curve_colour(c.name, 0);
  const Eigen::Index n = c.points.rows();
  ASSERT_GT(n, 20);
  for (Eigen::Index i = 0; i < n / 4; ++i) c.supported[static_cast<size_t>(i)] = false;
  const render::Scene scene = pipeline::overlay_scene(r);
  int named = 0, unnamed = 0, legend_only = 0;
  Eigen::Index points = 0;
  for (const auto& l : scene.polylines) {
    if (l.points.rows() == 0) {
      ++legend_only;
      EXPECT_FALSE(l.name.empty());
    } else if (l.name == c.name) {  // the run on the scan carries the name: the legend shows its colour
      ++named;
      EXPECT_EQ(l.colour, colour);
      EXPECT_FALSE(l.closed);
      points += l.points.rows();
    } else if (l.name.empty()) {  // the run off the scan: pale and thinner
      ++unnamed;
      EXPECT_EQ(l.colour, render::mix(colour, {255, 255, 255}, 0.5));
      EXPECT_LT(l.width_px, all_on.polylines[0].width_px);
      points += l.points.rows();
    }
  }
  EXPECT_EQ(named, 1);
  EXPECT_EQ(unnamed, 1);
  EXPECT_EQ(legend_only, 1);
  EXPECT_EQ(points, n + 2);  // the two runs share their end points
}

TEST(ReportFigures, AreDeterministic) {
  ReportFigureOptions o = small_options();
  o.parallel = false;  // one thread or six: the same bytes
  const auto again = pipeline::render_report_figures(test::report_test_result(), o);
  ASSERT_EQ(again.figures.size(), small_figures().figures.size());
  for (size_t i = 0; i < again.figures.size(); ++i) {
    EXPECT_EQ(again.figures[i].png, small_figures().figures[i].png) << i;
    EXPECT_EQ(again.figures[i].png, again.figures[i].image.encode_png()) << i;
  }
}

TEST(ReportFigures, RejectsInvalidOptions) {
  const auto& r = test::report_test_result();
  ReportFigureOptions o;
  o.size = 10;
  EXPECT_THROW(pipeline::render_report_figures(r, o), InvalidInput);
  o = {};
  o.distance_range_mm = 0;
  EXPECT_THROW(pipeline::render_report_figures(r, o), InvalidInput);
  o = {};
  o.side_size = 10;
  EXPECT_THROW(pipeline::render_report_figures(r, o), InvalidInput);
  o = {};
  o.supersample = 5;
  EXPECT_THROW(pipeline::render_report_figures(r, o), InvalidInput);
  pipeline::RegisterResult empty;
  EXPECT_THROW(pipeline::render_report_figures(empty), InvalidInput);
}

}  // namespace
}  // namespace breastfit
