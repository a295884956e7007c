// The report's figures on a real registration of a synthetic case: sizes, what each shows
// (drawing colours, landmark red, colour map), the distances behind the distance figure,
// off-scan parts of a drawing, determinism, option checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "breastfit/core/errors.h"
#include "breastfit/pipeline/report_figures.h"
#include "breastfit/render/colormap.h"
#include "breastfit/render/torso_overlays.h"
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

const pipeline::ReportFigures& small_figures() {
  static const pipeline::ReportFigures f = [] {
    ReportFigureOptions o;
    o.size = 400;
    return pipeline::render_report_figures(test::report_test_result(), o);
  }();
  return f;
}

TEST(ReportFigures, ThreeSquareFiguresOfTheRequestedSize) {
  const auto& figs = small_figures().figures;
  ASSERT_EQ(figs.size(), 3u);
  EXPECT_EQ(figs[0].id, "front");
  EXPECT_EQ(figs[1].id, "oblique");
  EXPECT_EQ(figs[2].id, "distance");
  for (const auto& f : figs) {
    EXPECT_EQ(f.image.width(), 400) << f.id;
    EXPECT_EQ(f.image.height(), 400) << f.id;
    EXPECT_FALSE(f.title.empty());
    EXPECT_FALSE(f.caption.empty());
  }
  EXPECT_NE(small_figures().body_frame.find("landmarks"), std::string::npos) << small_figures().body_frame;
}

TEST(ReportFigures, OverlayFiguresShowEveryDrawingAndTheLandmarks) {
  const auto& r = test::report_test_result();
  for (int k = 0; k < 2; ++k) {
    const render::Image& img = small_figures().figures[k].image;
    // Every drawing's colour appears (its line and its legend swatch).
    for (size_t c = 0; c < r.drawings_on_scan.size(); ++c)
      EXPECT_GT(count_near(img, pipeline::report_curve_colour(r.drawings_on_scan[c].name, c), 12), 20)
          << "figure " << k << " curve " << r.drawings_on_scan[c].name;
    EXPECT_GT(count_red(img), 40) << "figure " << k;
  }
}

TEST(ReportFigures, DistanceFigureUsesTheColourMapOverAFixedRange) {
  const render::Image& img = small_figures().figures[2].image;
  // The colour bar spans 0..10 mm: its two end colours are present.
  EXPECT_GE(count_near(img, render::colormap(render::Colormap::Viridis, 0.0, 0.0, 10.0), 3), 5);
  EXPECT_GE(count_near(img, render::colormap(render::Colormap::Viridis, 10.0, 0.0, 10.0), 3), 5);
  // Mostly close to the scan: the model's pixels are dominated by the dark end of the map.
  EXPECT_GT(count_near(img, render::colormap(render::Colormap::Viridis, 1.0, 0.0, 10.0), 40), 2000);
  // No landmark red: the distance figure is the colour map alone.
  EXPECT_EQ(count_red(img), 0);
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
  ReportFigureOptions o;
  o.size = 400;
  o.parallel = false;  // one thread or three: the same bytes
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
  o.supersample = 5;
  EXPECT_THROW(pipeline::render_report_figures(r, o), InvalidInput);
  pipeline::RegisterResult empty;
  EXPECT_THROW(pipeline::render_report_figures(empty), InvalidInput);
}

}  // namespace
}  // namespace breastfit
