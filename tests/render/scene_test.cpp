#include "breastfit/render/scene.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "breastfit/core/errors.h"
#include "breastfit/render/colormap.h"
#include "support/test_paths.h"
#include "support/test_shapes.h"

namespace breastfit::render {
namespace {

constexpr Rgb kMarker = {255, 0, 255};  // a colour the shaded skin never takes

RenderOptions small(View view = View::Front) {
  RenderOptions o;
  o.view = view;
  o.width = 256;
  o.height = 256;
  o.show_labels = false;
  o.show_orientation = false;
  return o;
}

Scene sphere_scene(const std::vector<Vec3>& markers) {
  Scene s;
  s.meshes.push_back({.name = "sphere", .mesh = test::sphere_mesh(100.0)});
  for (const Vec3& p : markers) s.points.push_back({.label = "", .position = p, .colour = kMarker, .radius_px = 5});
  return s;
}

/// Mean x and count of pixels close to the marker colour.
std::pair<double, int> marker_pixels(const Image& img, int min_strength = 200) {
  double sx = 0;
  int n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const Rgb c = img.at(x, y);
      if (c.r >= min_strength && c.b >= min_strength && c.g < 90) {
        sx += x;
        ++n;
      }
    }
  return {n ? sx / n : -1.0, n};
}

TEST(Scene, FrontViewShowsPatientRightOnTheLeft) {
  // Patient's right (x < 0) on the anterior surface (y < 0).
  const Image img = render_scene(sphere_scene({Vec3(-60, -80, 0)}), small(View::Front));
  const auto [mean_x, n] = marker_pixels(img);
  ASSERT_GT(n, 10);
  EXPECT_LT(mean_x, img.width() / 2.0);
}

TEST(Scene, SideViewShowsAnteriorOnTheRight) {
  // Side view from the patient's right: an anterior point (y < 0) on the right (x < 0) side.
  const Image img = render_scene(sphere_scene({Vec3(-60, -80, 0)}), small(View::Side));
  const auto [mean_x, n] = marker_pixels(img);
  ASSERT_GT(n, 10);
  EXPECT_GT(mean_x, img.width() / 2.0);
}

TEST(Scene, HiddenPointIsDimmedOrOmitted) {
  const Vec3 posterior(0, 100, 0);  // on the back of the sphere, hidden in the front view
  RenderOptions o = small(View::Front);
  o.show_hidden = false;
  EXPECT_EQ(marker_pixels(render_scene(sphere_scene({posterior}), o), 120).second, 0);
  o.show_hidden = true;
  const Image dimmed = render_scene(sphere_scene({posterior}), o);
  EXPECT_EQ(marker_pixels(dimmed).second, 0);  // never at full strength
  const Image plain = render_scene(sphere_scene({}), o);
  EXPECT_NE(dimmed.bytes(), plain.bytes());  // but visible as a tint
  // From the back it is fully visible.
  EXPECT_GT(marker_pixels(render_scene(sphere_scene({posterior}), small(View::Back))).second, 10);
}

TEST(Scene, DeterministicPngBytes) {
  Scene s = sphere_scene({Vec3(-60, -80, 0), Vec3(0, 100, 0)});
  s.points[0].label = "nipple_R";
  s.polylines.push_back({.name = "equator", .points = Points(), .closed = true});
  Points ring(120, 3);
  for (int i = 0; i < 120; ++i) ring.row(i) << 100 * std::cos(i * 0.0524), 100 * std::sin(i * 0.0524), 0;
  s.polylines[0].points = ring;
  RenderOptions o = small(View::Oblique);
  o.title = "determinism";
  o.show_labels = true;
  o.show_orientation = true;
  const auto a = render_scene(s, o).encode_png();
  const auto b = render_scene(s, o).encode_png();
  EXPECT_EQ(a, b);
  // Written and re-read unchanged.
  const auto path = test::temp_dir() / "scene.png";
  const Image img = render_scene(s, o);
  img.save_png(path);
  EXPECT_EQ(read_png(path).bytes(), img.bytes());
}

TEST(Scene, TwoPassesGiveRenderScene) {
  Scene s = sphere_scene({Vec3(-60, -80, 0), Vec3(0, 100, 0)});
  s.points[0].label = "nipple_R";
  Points ring(120, 3);
  for (int i = 0; i < 120; ++i) ring.row(i) << 100 * std::cos(i * 0.0524), 100 * std::sin(i * 0.0524), 0;
  s.polylines.push_back({.name = "equator", .points = ring, .closed = true});
  RenderOptions o = small(View::Oblique);
  o.title = "two passes";
  o.show_labels = true;
  o.show_orientation = true;
  const Image whole = render_scene(s, o);
  EXPECT_EQ(finish_scene(draw_scene_meshes(s, o), s, o).bytes(), whole.bytes());
  // The meshes' pass alone: the sphere, no marker; the overlays' pass may leave the meshes out.
  Scene meshes_only;
  meshes_only.meshes = s.meshes;
  meshes_only.polylines.push_back({.name = "equator", .points = Points(), .closed = true});  // the legend's band
  Rasterizer raster = draw_scene_meshes(meshes_only, o);
  EXPECT_GT(raster.surface_coverage(), 0.1);
  EXPECT_EQ(marker_pixels(raster.resolve()).second, 0);
  Scene overlays = s;
  overlays.meshes.clear();
  const Image two = finish_scene(std::move(raster), overlays, o);
  EXPECT_GT(marker_pixels(two).second, 20);
  // The ring and markers lie within the sphere's box and the legend's band was reserved: the same
  // camera and depth bias, so the same image as in one pass.
  EXPECT_EQ(two.bytes(), whole.bytes());
}

TEST(Scene, BodyToWorldTransformGivesTheSameView) {
  // The same scene rotated into a "scanner" frame, rendered with that body→world transform,
  // looks the same as the body-frame scene with the identity.
  Scene body = sphere_scene({Vec3(-60, -80, 0)});
  body.meshes[0].mesh = test::cube_mesh(80.0);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(1.1, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
  T.block<3, 1>(0, 3) = Vec3(400, -250, 90);
  Scene world = body;
  for (Eigen::Index i = 0; i < world.meshes[0].mesh.V.rows(); ++i)
    world.meshes[0].mesh.V.row(i) =
        (T.topLeftCorner<3, 3>() * world.meshes[0].mesh.V.row(i).transpose() + T.block<3, 1>(0, 3)).transpose();
  world.points[0].position = T.topLeftCorner<3, 3>() * body.points[0].position + T.block<3, 1>(0, 3);
  RenderOptions o = small(View::Oblique);
  const Image a = render_scene(body, o);
  o.body_to_world = T;
  const Image b = render_scene(world, o);
  int differ = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const Rgb p = a.at(x, y), q = b.at(x, y);
      differ += (std::abs(p.r - q.r) + std::abs(p.g - q.g) + std::abs(p.b - q.b)) > 30 ? 1 : 0;
    }
  EXPECT_LT(differ, a.width() * a.height() / 200);  // < 0.5 % (edge pixels)
}

TEST(Scene, ScalarsAndColourBar) {
  Scene s = sphere_scene({});
  ScalarField f;
  f.values.resize(s.meshes[0].mesh.V.rows());
  for (Eigen::Index i = 0; i < f.values.size(); ++i) f.values[i] = s.meshes[0].mesh.V(i, 2) / 10.0;  // −10..10
  f.map = Colormap::BlueWhiteRed;
  f.units = "mm";
  s.meshes[0].scalars = f;
  RenderOptions o = small();
  o.width = 400;
  o.height = 300;
  const Image img = render_scene(s, o);
  // The colour bar's hi end (red) appears unshaded somewhere in the right part of the image.
  const Rgb hi = colormap_unit(Colormap::BlueWhiteRed, 1.0), lo = colormap_unit(Colormap::BlueWhiteRed, 0.0);
  bool found_hi = false, found_lo = false;
  for (int y = 0; y < img.height(); ++y)
    for (int x = img.width() * 3 / 4; x < img.width(); ++x) {
      found_hi = found_hi || img.at(x, y) == hi;
      found_lo = found_lo || img.at(x, y) == lo;
    }
  EXPECT_TRUE(found_hi);
  EXPECT_TRUE(found_lo);
  // The top of the sphere is reddish, the bottom bluish.
  int top_red = 0, bottom_blue = 0;
  for (int x = 0; x < img.width(); ++x) {
    for (int y = 0; y < img.height() / 3; ++y) {
      const Rgb c = img.at(x, y);
      top_red += (c.r > c.b + 40) ? 1 : 0;
    }
    for (int y = 2 * img.height() / 3; y < img.height(); ++y) {
      const Rgb c = img.at(x, y);
      bottom_blue += (c.b > c.r + 40) ? 1 : 0;
    }
  }
  EXPECT_GT(top_red, 1000);
  EXPECT_GT(bottom_blue, 1000);
  // Without the colour bar the right part has no pure endpoint colours.
  o.show_colorbar = false;
  const Image bare = render_scene(s, o);
  EXPECT_NE(bare.bytes(), img.bytes());
  // Wrong scalar count.
  s.meshes[0].scalars->values.resize(3);
  EXPECT_THROW(render_scene(s, o), InvalidInput);
}

TEST(Scene, TitleAndLabelsAreDrawn) {
  const Scene s = sphere_scene({Vec3(-60, -80, 0)});
  RenderOptions o = small();
  const Image plain = render_scene(s, o);
  o.title = "TITLE";
  const Image titled = render_scene(s, o);
  auto dark_in = [](const Image& img, int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) n += (img.at(x, y).r < 60 && img.at(x, y).g < 60) ? 1 : 0;
    return n;
  };
  EXPECT_EQ(dark_in(plain, 0, 0, 60, 14), 0);
  EXPECT_GT(dark_in(titled, 0, 0, 60, 14), 20);
  // A title too long for the image is scaled down and cut, never drawn past the right edge.
  o.title = std::string(200, 'W');
  const Image long_title = render_scene(s, o);
  EXPECT_GT(dark_in(long_title, 0, 0, 256, 14), 100);
  EXPECT_EQ(dark_in(long_title, 250, 0, 256, 14), 0);
  Scene labelled = s;
  labelled.points[0].label = "nipple_R";
  o.title.clear();
  o.show_labels = true;
  const Image with_label = render_scene(labelled, o);
  EXPECT_GT(dark_in(with_label, 0, 0, 256, 256), dark_in(plain, 0, 0, 256, 256) + 30);
}

TEST(Scene, TheLegendFlowsAlongTheBottomAndNeverCoversTheScene) {
  // A sphere that fills the frame and a legend with many long entries: the framing keeps the
  // legend's box free of the sphere's silhouette, in every view and size.
  for (int size : {256, 512})
    for (View v : {View::Front, View::Side, View::ObliqueLeft}) {
      Scene s = sphere_scene({});
      for (const char* name : {"breast_contour_R", "breast_contour_L", "imf_R", "imf_L", "sternum",
                               "pale: no scan under it", "placed landmark (line to fitted)"}) {
        ScenePolyline l;
        l.name = name;
        l.points.resize(2, 3);
        l.points << -50, -101, 0, 50, -101, 0;
        s.polylines.push_back(l);
      }
      RenderOptions o = small(v);
      o.width = o.height = size;
      o.show_orientation = true;
      o.title = "a title";
      const auto box = legend_box(s, o);
      ASSERT_TRUE(box);
      EXPECT_GE(box->min().x(), 0);
      EXPECT_LE(box->max().x(), size);
      EXPECT_LE(box->max().y(), size);
      RenderOptions bare = o;
      bare.camera = scene_camera(s, o);
      bare.show_legend = bare.show_orientation = false;
      bare.title.clear();
      const Image silhouette = render_scene(s, bare);
      int inside = 0, any = 0;
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const bool body = !(silhouette.at(x, y) == o.background);
          any += body;
          inside += body && box->contains(Eigen::Vector2i(x, y)) && x < box->max().x() && y < box->max().y();
        }
      EXPECT_EQ(inside, 0) << view_name(v) << " " << size;
      EXPECT_GT(any, size * size / 5);  // the sphere still fills much of the image
    }
  // No named polyline: no legend box, no space kept.
  EXPECT_FALSE(legend_box(sphere_scene({}), small()));
}

TEST(Scene, TheViewCaptionCanSayTheOrientationIsUnknown) {
  const Scene s = sphere_scene({});
  RenderOptions o = small();
  o.show_orientation = true;
  const Image front = render_scene(s, o);
  o.view_caption = "view: orientation unknown";
  const Image unknown = render_scene(s, o);
  EXPECT_NE(front.bytes(), unknown.bytes());
  o.view_caption = std::string(view_name(View::Front)) + " view";
  EXPECT_EQ(render_scene(s, o).bytes(), front.bytes());
}

TEST(Scene, PerspectiveAndWorldSizedPoints) {
  Scene s = sphere_scene({Vec3(0, -100, 0)});
  RenderOptions o = small(View::Front);
  const auto [x_px, n_px] = marker_pixels(render_scene(s, o));
  s.points[0].radius_unit = SizeUnit::World;
  s.points[0].radius_px = 20.0;  // 20 mm: a tenth of the sphere's diameter
  o.projection = Projection::Perspective;
  o.fov_y_deg = 25;
  const Image img = render_scene(s, o);
  const auto [x_mm, n_mm] = marker_pixels(img, 110);
  EXPECT_NEAR(x_mm, 128.0, 3.0);  // centred
  EXPECT_GT(n_mm, 4 * n_px);      // a 20 mm disc is much larger than a 5 px one here
  // The sphere fills the framed image without touching its border.
  for (int x = 0; x < img.width(); ++x) {
    EXPECT_EQ(img.at(x, 0), (Rgb{255, 255, 255}));
    EXPECT_EQ(img.at(x, img.height() - 1), (Rgb{255, 255, 255}));
  }
  EXPECT_NE(img.at(128, 128), (Rgb{255, 255, 255}));
}

TEST(Scene, InvalidInput) {
  EXPECT_THROW(render_scene(Scene{}, small()), InvalidInput);
  RenderOptions o = small();
  o.width = 0;
  EXPECT_THROW(render_scene(sphere_scene({}), o), InvalidInput);
  o = small();
  o.margin = 0.6;
  EXPECT_THROW(render_scene(sphere_scene({}), o), InvalidInput);
}

}  // namespace
}  // namespace breastfit::render
