#include "breastfit/render/rasterizer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "breastfit/core/errors.h"
#include "render/render_test_camera.h"
#include "support/test_shapes.h"

namespace breastfit::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

using test::front_camera;

RasterOptions small_options(int size = 200) {
  RasterOptions o;
  o.width = size;
  o.height = size;
  o.background = {255, 255, 255};
  return o;
}

int count_not(const Image& img, Rgb c) {
  int n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) n += img.at(x, y) == c ? 0 : 1;
  return n;
}

TEST(Rasterizer, CubeSilhouetteCoverage) {
  Rasterizer r(front_camera(2.0), small_options());
  r.draw_mesh(test::cube_mesh(0.5));
  // A unit square in a 2×2 view: a quarter of the image.
  EXPECT_NEAR(r.surface_coverage(), 0.25, 0.005);
  const Image img = r.resolve();
  EXPECT_NEAR(count_not(img, {255, 255, 255}) / 40000.0, 0.25, 0.01);
  EXPECT_NE(img.at(100, 100), (Rgb{255, 255, 255}));
  EXPECT_EQ(img.at(10, 10), (Rgb{255, 255, 255}));
}

TEST(Rasterizer, SphereSilhouetteCoverage) {
  for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
    Camera cam = front_camera(3.0);
    if (proj == Projection::Perspective) {
      cam.projection = proj;
      // At distance 50 a 1-unit sphere spans 2·asin(1/50); choose the fov so it fills 2/3.
      cam.fov_y_deg = 2.0 * std::atan(1.5 / std::sqrt(50.0 * 50.0 - 1.0)) * 180.0 / kPi;
    }
    Rasterizer r(cam, small_options(300));
    r.draw_mesh(test::sphere_mesh(1.0));
    const double expected = kPi * 1.0 / 9.0;  // π r² / (3 × 3)
    EXPECT_NEAR(r.surface_coverage(), expected, 0.01 * expected) << static_cast<int>(proj);
  }
}

TEST(Rasterizer, ShadingIsBrightestFacingTheCamera) {
  Rasterizer r(front_camera(3.0), small_options(300));
  r.draw_mesh(test::sphere_mesh(1.0));
  const Image img = r.resolve();
  auto lum = [&](int x, int y) { const Rgb c = img.at(x, y); return c.r + c.g + c.b; };
  EXPECT_GT(lum(150, 150), lum(150 + 95, 150));  // centre vs near the rim
  EXPECT_GT(lum(150, 150), lum(150, 150 + 95));
}

TEST(Rasterizer, BackFacesAreDarkerAndTinted) {
  SurfaceStyle style;
  style.specular = 0;
  Rasterizer front(front_camera(2.0), small_options(50));
  front.draw_mesh(test::square_mesh(0.5, 0.0), style);  // normal −y: faces the camera
  TriangleMesh flipped = test::square_mesh(0.5, 0.0);
  flipped.F.col(1).swap(flipped.F.col(2));
  Rasterizer back(front_camera(2.0), small_options(50));
  back.draw_mesh(flipped, style);
  const Rgb f = front.resolve().at(25, 25), b = back.resolve().at(25, 25);
  EXPECT_GT(f.r + f.g + f.b, b.r + b.g + b.b + 60);
  EXPECT_GT(b.b, b.r);  // cool tint
  EXPECT_GT(f.r, f.b);  // skin tone
}

// Back faces are drawn after the front faces and skipped where they lie behind everything drawn
// in their screen area; one nearer than a front face must still show (e.g. the inside of an
// open surface), with either projection (the facing comes from the winding in the image).
TEST(Rasterizer, BackFaceNearerThanAFrontFaceIsDrawn) {
  SurfaceStyle style;
  style.specular = 0;
  TriangleMesh far = test::square_mesh(0.8, 0.5);   // faces the camera, behind
  TriangleMesh near = test::square_mesh(0.3, -0.2);  // turned away from the camera, in front
  near.F.col(1).swap(near.F.col(2));
  TriangleMesh both;
  both.V.resize(far.V.rows() + near.V.rows(), 3);
  both.V << far.V, near.V;
  both.F.resize(far.F.rows() + near.F.rows(), 3);
  both.F << near.F.array() + static_cast<int>(far.V.rows()), far.F;  // the back face listed first
  for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
    Camera cam = front_camera(2.0);
    cam.projection = proj;
    cam.fov_y_deg = 2.0 * std::atan(1.0 / 50.0) * 180.0 / kPi;
    Rasterizer r(cam, small_options(100));
    r.draw_mesh(both, style);
    const Image img = r.resolve();
    const Rgb centre = img.at(50, 50), rim = img.at(50, 15);
    EXPECT_GT(centre.b, centre.r) << static_cast<int>(proj);  // the back face's cool tint
    EXPECT_GT(rim.r, rim.b) << static_cast<int>(proj);        // skin around it
  }
}

/// The largest channel difference between two images of the same size.
int worst_difference(const Image& a, const Image& b) {
  int worst = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const Rgb p = a.at(x, y), q = b.at(x, y);
      worst = std::max({worst, std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
    }
  return worst;
}

/// The worst channel difference between `mesh` drawn supersampled (2×) and drawn at twice the
/// size without supersampling, then box-filtered: what lighting a pixel once costs against
/// shading every sample and averaging. Also counts the pixels drawn.
int worst_against_per_sample_shading(const TriangleMesh& mesh, Projection proj, int* drawn) {
  Camera cam = front_camera(3.0);
  cam.eye = Vec3(-20, -40, 15);
  cam.projection = proj;
  cam.fov_y_deg = 2.0 * std::atan(1.5 / 48.0) * 180.0 / kPi;
  RasterOptions ss2 = small_options(96);
  ss2.supersample = 2;
  RasterOptions big = small_options(192);
  big.supersample = 1;
  Rasterizer a(cam, ss2), b(cam, big);
  a.draw_mesh(mesh);
  b.draw_mesh(mesh);
  const Image ia = a.resolve(), ib = b.resolve().downsampled(2);
  *drawn = count_not(ia, {255, 255, 255});
  return worst_difference(ia, ib);
}

/// A unit sphere coloured by height, `rings` × `segments` quads.
TriangleMesh coloured_sphere(int rings, int segments) {
  TriangleMesh sphere = test::sphere_mesh(1.0, Vec3::Zero(), rings, segments);
  sphere.C = Colors::Zero(sphere.V.rows(), 3);
  for (Eigen::Index i = 0; i < sphere.V.rows(); ++i)  // colour varying across the surface
    sphere.C.row(i) << 200, static_cast<std::uint8_t>(120 + 100 * sphere.V(i, 2)), 90;
  return sphere;
}

// An output pixel whose samples all lie on one smooth patch is lit once with their mean normal
// and colour: within a couple of grey levels of shading every sample and averaging (the same
// scene drawn at twice the size without supersampling, then box-filtered).
TEST(Rasterizer, PixelsLitOnceMatchPerSampleShading) {
  for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
    int drawn = 0;
    EXPECT_LE(worst_against_per_sample_shading(coloured_sphere(24, 48), proj, &drawn), 2) << static_cast<int>(proj);
    EXPECT_GT(drawn, 1000);
  }
}

// The same with triangles smaller than a pixel (a dense scan in a small figure): a pixel of
// several triangles samples each once, at the mean position of its samples on it.
TEST(Rasterizer, PixelsOfTinyTrianglesMatchPerSampleShading) {
  const TriangleMesh dense = coloured_sphere(160, 320);  // ~100k triangles, ~1 sample each
  for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
    int drawn = 0;
    EXPECT_LE(worst_against_per_sample_shading(dense, proj, &drawn), 2) << static_cast<int>(proj);
    EXPECT_GT(drawn, 1000);
  }
}

// A fan of thin triangles around a point, corners at arbitrary sub-sample positions: every
// sample inside the fan is covered by one of them (no cracks along the shared edges).
TEST(Rasterizer, TrianglesSharingEdgesLeaveNoCracks) {
  constexpr int kSpokes = 257;
  TriangleMesh fan;
  fan.V.resize(kSpokes + 1, 3);
  fan.V.row(0) = Vec3(0.0123, 0, -0.0071).transpose();
  for (int k = 0; k < kSpokes; ++k) {
    const double a = 2 * kPi * k / kSpokes;
    fan.V.row(k + 1) = Vec3(0.9 * std::cos(a), 0, 0.9 * std::sin(a)).transpose();
  }
  fan.F.resize(kSpokes, 3);
  for (int k = 0; k < kSpokes; ++k) fan.F.row(k) << 0, 1 + (k + 1) % kSpokes, 1 + k;  // facing −y (the camera)
  RasterOptions o = small_options(211);
  o.supersample = 1;
  Rasterizer r(front_camera(2.0), o);
  r.draw_mesh(fan);
  const Image img = r.resolve();
  int holes = 0, inside = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const double px = (x + 0.5) / img.width() * 2.0 - 1.0, pz = 1.0 - (y + 0.5) / img.height() * 2.0;
      if (std::hypot(px, pz) > 0.85) continue;  // well inside the polygon
      ++inside;
      holes += img.at(x, y) == Rgb{255, 255, 255} ? 1 : 0;
    }
  EXPECT_GT(inside, 15000);
  EXPECT_EQ(holes, 0);
}

TEST(Rasterizer, VertexColoursAreInterpolated) {
  TriangleMesh sq = test::square_mesh(0.5, 0.0);
  sq.C.resize(4, 3);
  sq.C << 255, 0, 0, 255, 0, 0, 0, 0, 255, 0, 0, 255;  // bottom red, top blue
  Rasterizer r(front_camera(1.2), small_options(100));
  r.draw_mesh(sq);
  const Image img = r.resolve();
  const Rgb low = img.at(50, 85), high = img.at(50, 15);
  EXPECT_GT(low.r, low.b + 100);
  EXPECT_GT(high.b, high.r + 100);
}

/// Pixels whose largest channel difference between `a` and `b` exceeds `levels`.
int pixels_differing(const Image& a, const Image& b, int levels) {
  int n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const Rgb p = a.at(x, y), q = b.at(x, y);
      n += std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)}) > levels ? 1 : 0;
    }
  return n;
}

/// Pixels of `img` that are neither `a` nor `b` (anti-aliased edge pixels between them).
int count_between(const Image& img, Rgb a, Rgb b) {
  int n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) n += (img.at(x, y) == a || img.at(x, y) == b) ? 0 : 1;
  return n;
}

/// `meshes` drawn one draw_mesh each, with supersampling at the edges only or at every sample.
Image draw_meshes(const std::vector<TriangleMesh>& meshes, const Camera& cam, int size, bool adaptive,
                  const SurfaceStyle& style = {}) {
  RasterOptions o = small_options(size);
  o.adaptive_supersample = adaptive;
  Rasterizer r(cam, o);
  for (const TriangleMesh& m : meshes) r.draw_mesh(m, style);
  return r.resolve();
}

/// One uniformly lit colour: flat faces facing the camera, no highlight.
SurfaceStyle flat_style(Rgb colour) {
  SurfaceStyle s;
  s.colour = colour;
  s.smooth = false;
  s.specular = 0;
  return s;
}

/// A square [-h, h]^2 in the plane y = y0 turned by `angle` about the y axis (facing −y).
TriangleMesh turned_square(double h, double y0, double angle) {
  TriangleMesh m = test::square_mesh(h, y0);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    const double x = m.V(i, 0), z = m.V(i, 2);
    m.V(i, 0) = std::cos(angle) * x - std::sin(angle) * z;
    m.V(i, 2) = std::sin(angle) * x + std::cos(angle) * z;
  }
  return m;
}

// Supersampling only at edges: a silhouette's pixels keep their intermediate (anti-aliased)
// values, as many as with every sample supersampled, and the same values.
TEST(Rasterizer, AdaptiveSupersamplingKeepsSilhouettesAntiAliased) {
  const SurfaceStyle style = flat_style({200, 60, 40});
  const std::vector<TriangleMesh> square = {turned_square(0.6, 0.0, 0.3)};
  const Image adaptive = draw_meshes(square, front_camera(2.0), 101, true, style);
  const Image full = draw_meshes(square, front_camera(2.0), 101, false, style);
  const Rgb inside = full.at(50, 50), background{255, 255, 255};
  const int edge_full = count_between(full, inside, background);
  EXPECT_GT(edge_full, 150);  // the turned square's outline, ≈ 4 × 61 pixels, most of them partly covered
  EXPECT_EQ(count_between(adaptive, inside, background), edge_full);
  EXPECT_LE(worst_difference(adaptive, full), 1);
}

// A fold: a nearer part of the same mesh over a farther one (same coverage and facing on both
// sides of the edge, only the depth jumps) is anti-aliased too.
TEST(Rasterizer, AdaptiveSupersamplingRefinesDepthJumps) {
  TriangleMesh far = test::square_mesh(1.5, 0.5), near = turned_square(0.4, -0.3, 0.4);  // far: the whole view
  far.C = Colors::Constant(far.V.rows(), 3, 40);
  near.C = Colors::Constant(near.V.rows(), 3, 220);
  TriangleMesh both;
  both.V.resize(far.V.rows() + near.V.rows(), 3);
  both.V << far.V, near.V;
  both.C.resize(both.V.rows(), 3);
  both.C << far.C, near.C;
  both.F.resize(far.F.rows() + near.F.rows(), 3);
  both.F << far.F, near.F.array() + static_cast<int>(far.V.rows());
  SurfaceStyle style = flat_style({0, 0, 0});
  const Image adaptive = draw_meshes({both}, front_camera(2.0), 101, true, style);
  const Image full = draw_meshes({both}, front_camera(2.0), 101, false, style);
  const Rgb dark = full.at(5, 5), light = full.at(50, 50);
  const int edge_full = count_between(full, dark, light);
  EXPECT_GT(edge_full, 80);
  EXPECT_EQ(count_between(adaptive, dark, light), edge_full);
  EXPECT_LE(worst_difference(adaptive, full), 1);
}

// Smooth shading, vertex colours, silhouettes, back faces through holes and triangles smaller
// than a pixel: within a few grey levels of supersampling every sample, and the same coverage.
TEST(Rasterizer, AdaptiveSupersamplingMatchesFullSupersampling) {
  for (const auto& [rings, segments] : {std::pair{24, 48}, std::pair{160, 320}}) {
    TriangleMesh sphere = coloured_sphere(rings, segments);
    // Holes: every 7th triangle left out (the inside, back faces, shows through).
    Triangles kept(sphere.F.rows(), 3);
    Eigen::Index n = 0;
    for (Eigen::Index f = 0; f < sphere.F.rows(); ++f)
      if (f % 7 != 3 || rings > 100) kept.row(n++) = sphere.F.row(f);
    sphere.F = kept.topRows(n);
    Camera cam = front_camera(3.0);
    cam.eye = Vec3(-20, -40, 15);
    Rasterizer a(cam, small_options(150));
    RasterOptions o = small_options(150);
    o.adaptive_supersample = false;
    Rasterizer b(cam, o);
    a.draw_mesh(sphere);
    b.draw_mesh(sphere);
    EXPECT_NEAR(a.surface_coverage(), b.surface_coverage(), 0.002) << rings;
    const Image ia = a.resolve(), ib = b.resolve();
    EXPECT_GT(count_not(ib, {255, 255, 255}), 7000);
    // A hole thinner than a pixel between pixel centres (on the steep rim) is missed by the
    // one-sample pass: those few pixels differ (0.2 %); all others within a few grey levels.
    EXPECT_LE(pixels_differing(ia, ib, 3), rings > 100 ? 0 : 24) << rings;  // of ≈ 7 800 (15 measured)
    if (rings > 100) EXPECT_LE(worst_difference(ia, ib), 3);
  }
}

// Only the first mesh on empty buffers takes the adaptive path: a second draw_mesh over it is
// drawn as with every sample supersampled (the first mesh's pixels unchanged where not drawn over).
TEST(Rasterizer, AdaptiveSupersamplingWithSeveralMeshes) {
  const SurfaceStyle red = flat_style({200, 60, 40});
  const std::vector<TriangleMesh> meshes = {turned_square(0.6, 0.0, 0.3), turned_square(0.3, -0.1, -0.2),
                                            turned_square(0.8, 0.2, 0.1)};  // in front, then partly behind
  const Image adaptive = draw_meshes(meshes, front_camera(2.0), 101, true, red);
  const Image full = draw_meshes(meshes, front_camera(2.0), 101, false, red);
  EXPECT_LE(worst_difference(adaptive, full), 1);
  const Rgb inside = full.at(50, 50), background{255, 255, 255};
  EXPECT_EQ(count_between(adaptive, inside, background), count_between(full, inside, background));
}

// Perspective views (and supersample 1) take the full path: the same bytes either way.
TEST(Rasterizer, AdaptiveSupersamplingLeavesPerspectiveViewsAlone) {
  Camera cam = front_camera(3.0);
  cam.eye = Vec3(-20, -40, 15);
  cam.projection = Projection::Perspective;
  cam.fov_y_deg = 2.0 * std::atan(1.5 / 48.0) * 180.0 / kPi;
  const std::vector<TriangleMesh> sphere = {coloured_sphere(24, 48)};
  EXPECT_EQ(draw_meshes(sphere, cam, 96, true).encode_png(), draw_meshes(sphere, cam, 96, false).encode_png());
}

TEST(Rasterizer, PointBehindTheSurfaceIsHiddenOrDimmed) {
  const Vec3 behind(0, 1.0, 0), in_front(0, -1.0, 0);
  const PointStyle red{{255, 0, 0}, 5.0, SizeUnit::Pixels};
  for (bool show_hidden : {false, true}) {
    RasterOptions o = small_options(100);
    o.show_hidden_overlays = show_hidden;
    o.hidden_alpha = 0.3;
    Rasterizer r(front_camera(2.0), o);
    r.draw_mesh(test::square_mesh(0.5, 0.0));
    const Rgb surface = r.resolve().at(50, 50);
    EXPECT_FALSE(r.is_visible(behind));
    EXPECT_TRUE(r.is_visible(in_front));
    r.draw_point(behind, red);
    const Rgb seen = r.resolve().at(50, 50);
    if (!show_hidden) {
      EXPECT_EQ(seen, surface);
    } else {
      EXPECT_NE(seen, surface);
      EXPECT_GT(seen.r, seen.g + 20);     // tinted towards red
      EXPECT_LT(seen.r - seen.g, 200);    // but not the full red
    }
    r.draw_point(in_front, red);
    const Rgb front = r.resolve().at(50, 50);
    EXPECT_GT(front.r, 150);
    EXPECT_LT(front.g, 80);
  }
}

TEST(Rasterizer, DepthBiasKeepsPointsOnTheSkinVisible) {
  RasterOptions o = small_options(100);
  o.depth_bias = 0.05;
  Rasterizer r(front_camera(2.0), o);
  r.draw_mesh(test::square_mesh(0.5, 0.0));
  EXPECT_TRUE(r.is_visible(Vec3(0, 0.03, 0)));   // 0.03 behind, within the bias
  EXPECT_FALSE(r.is_visible(Vec3(0, 0.08, 0)));  // beyond the bias
  EXPECT_FALSE(r.is_visible(Vec3(5, 0, 0)));     // outside the image
}

TEST(Rasterizer, PolylineIsDrawnWithItsWidth) {
  Rasterizer r(front_camera(2.0), small_options(100));
  Points line(2, 3);
  line << -0.8, -1, 0, 0.8, -1, 0;  // horizontal through the centre, in front of nothing
  LineStyle style;
  style.colour = {0, 0, 255};
  style.width_px = 4;
  r.draw_polyline(line, false, style);
  const Image img = r.resolve();
  EXPECT_EQ(img.at(50, 50), (Rgb{0, 0, 255}));
  EXPECT_EQ(img.at(50, 48), (Rgb{0, 0, 255}));
  EXPECT_EQ(img.at(50, 54), (Rgb{255, 255, 255}));
  EXPECT_EQ(img.at(5, 50), (Rgb{255, 255, 255}));  // beyond the end (x = −0.8 → pixel 10)
  EXPECT_THROW(r.draw_polyline(line, false, {{0, 0, 0}, 0.0}), InvalidInput);
}

TEST(Rasterizer, PointCloudSplats) {
  TriangleMesh cloud;
  cloud.V.resize(3, 3);
  cloud.V << -0.5, 0, 0, 0, 0, 0, 0.5, 0, 0;
  SurfaceStyle style;
  style.point_radius_px = 3;
  Rasterizer r(front_camera(2.0), small_options(100));
  r.draw_mesh(cloud, style);
  EXPECT_GT(r.surface_coverage(), 3 * 25.0 / 10000.0);
  EXPECT_LT(r.surface_coverage(), 3 * 35.0 / 10000.0);
}

TEST(Rasterizer, WireframeDrawsEdgesOnlyWhereVisible) {
  // Front square (diagonal from image bottom-left to top-right) hiding a back square whose
  // diagonal runs the other way.
  const TriangleMesh front = test::square_mesh(0.5, 0.0);
  TriangleMesh back = test::square_mesh(0.5, 1.0);
  back.F << 0, 1, 3, 1, 2, 3;
  Rasterizer r(front_camera(2.0), small_options(100));
  r.draw_mesh(front);
  r.draw_mesh(back);
  const Image before = r.resolve();
  r.draw_wireframe(front.V, front.F, {{0, 0, 0}, 1.0, 3.0});
  r.draw_wireframe(back.V, back.F, {{0, 0, 0}, 1.0, 3.0});
  const Image after = r.resolve();
  auto lum = [](Rgb c) { return c.r + c.g + c.b; };
  EXPECT_LT(lum(after.at(40, 60)), lum(before.at(40, 60)) / 3);  // on the front diagonal
  EXPECT_EQ(after.at(40, 40), before.at(40, 40));                 // on the hidden back diagonal
  EXPECT_THROW(r.draw_wireframe(front.V, front.F, {{0, 0, 0}, 0.0, 1.0}), InvalidInput);
}

TEST(Rasterizer, Deterministic) {
  auto render = [] {
    Camera cam = front_camera(3.0);
    cam.eye = Vec3(-30, -40, 20);
    Rasterizer r(cam, small_options(128));
    r.draw_mesh(test::sphere_mesh(1.0));
    Points ring(50, 3);
    for (int i = 0; i < 50; ++i) ring.row(i) << std::cos(i * 0.1257), std::sin(i * 0.1257), 0;
    r.draw_polyline(ring, true);
    r.draw_point(Vec3(0, -1, 0));
    return r.resolve().encode_png();
  };
  EXPECT_EQ(render(), render());
}

TEST(Rasterizer, SurvivesNonFiniteAndBehindTheCameraGeometry) {
  Camera cam = front_camera(2.0);
  cam.projection = Projection::Perspective;
  cam.fov_y_deg = 40;
  cam.eye = Vec3(0, -2, 0);  // the unit square fills about half the view
  Rasterizer r(cam, small_options(64));
  TriangleMesh m = test::square_mesh(0.5, 0.0);
  m.V.conservativeResize(6, 3);
  m.V.row(4) << std::nan(""), 0, 0;
  m.V.row(5) << 0, -80, 0;  // behind the eye
  m.F.conservativeResize(4, 3);
  m.F.row(2) << 0, 1, 4;
  m.F.row(3) << 0, 5, 2;
  r.draw_mesh(m);
  Points line(3, 3);
  line << 0, 0, 0, 0, -80, 0, 1e300, 0, 0;
  r.draw_polyline(line, true);
  r.draw_point(Vec3(0, -80, 0));
  r.draw_point(Vec3(1e300, 0, 0));
  // The valid square is still drawn.
  EXPECT_GT(r.surface_coverage(), 0.3);
  EXPECT_FALSE(r.is_visible(Vec3(0, -80, 0)));
}

TEST(Rasterizer, RejectsBadInput) {
  EXPECT_THROW(Rasterizer(front_camera(-1.0), small_options()), InvalidInput);
  RasterOptions o = small_options();
  o.supersample = 0;
  EXPECT_THROW(Rasterizer(front_camera(1.0), o), InvalidInput);
  Rasterizer r(front_camera(2.0), small_options());
  TriangleMesh bad = test::cube_mesh();
  bad.F(0, 0) = 99;
  EXPECT_THROW(r.draw_mesh(bad), InvalidInput);
  TriangleMesh wrong_colours = test::cube_mesh();
  wrong_colours.C.resize(3, 3);
  EXPECT_THROW(r.draw_mesh(wrong_colours.V, wrong_colours.F, Points(), wrong_colours.C), InvalidInput);
}

}  // namespace
}  // namespace breastfit::render
