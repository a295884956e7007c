// A draw_mesh call's prepared triangles: which are drawn, their facing and drawing order (front
// faces first, by screen tile), the corner stream, and the surface sampled on a triangle.
#include "breastfit/render/detail/surface_draw.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "render/render_test_camera.h"

namespace breastfit::render::detail {
namespace {

/// A small triangle around (x, z) facing the camera (−y), or away from it.
void add_triangle(Points& V, Triangles& F, double x, double z, bool facing) {
  const Eigen::Index n = V.rows();
  V.conservativeResize(n + 3, 3);
  V.row(n) = Vec3(x - 0.05, 0, z - 0.05);
  V.row(n + 1) = Vec3(x + 0.05, 0, z - 0.05);
  V.row(n + 2) = Vec3(x, 0, z + 0.05);
  F.conservativeResize(F.rows() + 1, 3);
  F.row(F.rows() - 1) = facing ? Eigen::RowVector3i(n, n + 1, n + 2) : Eigen::RowVector3i(n, n + 2, n + 1);
}

TEST(SurfaceDraw, FrontFacesFirstThenByTile) {
  Points V(0, 3);
  Triangles F(0, 3);
  add_triangle(V, F, 0.8, -0.8, false);  // 0: back face, lower right
  add_triangle(V, F, 0.8, 0.8, true);    // 1: upper right
  add_triangle(V, F, -0.8, 0.8, true);   // 2: upper left
  add_triangle(V, F, -0.8, -0.8, false);  // 3: back face, lower left
  add_triangle(V, F, 0.8, 0.8, true);    // 4: upper right, after 1 in the same tile
  const SurfaceStyle style;
  const Camera camera = test::front_camera(2.0);
  const Points no_normals;
  const Colors no_colours;
  const SurfaceDraw draw(camera, V, F, no_normals, no_colours, style, 128, 128);  // 4 × 4 tiles
  EXPECT_EQ(draw.tiles, 16);
  EXPECT_EQ(draw.n_front, 3u);
  EXPECT_EQ(draw.order, (std::vector<std::int32_t>{2, 1, 4, 3, 0}));
  for (std::int32_t t : {1, 2, 4}) {
    EXPECT_TRUE(draw.is_front(t));
    EXPECT_LT(draw.area[static_cast<size_t>(t)], 0);
  }
  EXPECT_FALSE(draw.is_front(0));
  EXPECT_GT(draw.area[0], 0);
  // Bucket b is order[bucket_end[b − 1], bucket_end[b]): upper left (tile 0), upper right (tile 3)
  // of the front faces, then lower left (tile 12) and lower right (tile 15) of the back faces.
  EXPECT_EQ(draw.bucket_end[0], 1);
  EXPECT_EQ(draw.bucket_end[3], 3);
  EXPECT_EQ(draw.bucket_end[16 + 12], 4);
  EXPECT_EQ(draw.bucket_end[16 + 15], 5);
  EXPECT_TRUE(draw.all_fixed);
}

TEST(SurfaceDraw, SkipsDegenerateNonFiniteAndBehindTheCameraTriangles) {
  Points V(0, 3);
  Triangles F(0, 3);
  add_triangle(V, F, 0.0, 0.0, true);  // 0: drawn
  add_triangle(V, F, 0.3, 0.3, true);  // 1: collapsed to a segment
  V.row(5) = V.row(3);
  add_triangle(V, F, -0.3, 0.3, true);  // 2: a non-finite corner
  V(6, 0) = std::numeric_limits<double>::quiet_NaN();
  add_triangle(V, F, 0.3, -0.3, true);  // 3: behind a perspective camera
  V.row(11) = Vec3(0.3, -60, -0.3);
  Camera camera = test::front_camera(2.0);
  camera.projection = Projection::Perspective;
  const SurfaceStyle style;
  const Points no_normals;
  const Colors no_colours;
  const SurfaceDraw draw(camera, V, F, no_normals, no_colours, style, 64, 64);
  EXPECT_EQ(draw.order, (std::vector<std::int32_t>{0}));
  EXPECT_EQ(draw.area[1], 0.0);
  EXPECT_EQ(draw.area[2], 0.0);
  EXPECT_EQ(draw.area[3], 0.0);
}

TEST(SurfaceDraw, CornerStreamFollowsTheDrawingOrder) {
  Points V(0, 3);
  Triangles F(0, 3);
  for (int i = 0; i < 5000; ++i) add_triangle(V, F, -0.9 + 1.8 * ((i * 37) % 100) / 100.0, -0.9 + 1.8 * (i % 97) / 97.0, i % 3 != 0);
  const SurfaceStyle style;
  const Camera camera = test::front_camera(2.0);
  const Points no_normals;
  const Colors no_colours;
  const SurfaceDraw draw(camera, V, F, no_normals, no_colours, style, 256, 256);
  ASSERT_EQ(draw.order.size(), 5000u);
  CornerStream corners(draw);
  for (size_t k = 0; k < draw.order.size(); ++k) {
    const std::array<Projected, 3>& c = corners.at(k);
    for (int j = 0; j < 3; ++j) {
      const Projected& p = draw.P[draw.F(draw.order[k], j)];
      ASSERT_EQ(c[j].x, p.x);
      ASSERT_EQ(c[j].y, p.y);
      ASSERT_EQ(c[j].depth, p.depth);
    }
  }
}

TEST(SurfaceDraw, SamplesInterpolateColoursAndFaceTheViewer) {
  Points V(0, 3);
  Triangles F(0, 3);
  add_triangle(V, F, 0.0, 0.0, false);  // a back face
  Colors C(3, 3);
  C << 255, 0, 0, 0, 255, 0, 0, 0, 255;
  SurfaceStyle style;
  style.smooth = false;
  const Camera camera = test::front_camera(2.0);
  const Points no_normals;
  const SurfaceDraw draw(camera, V, F, no_normals, C, style, 100, 100);
  const Projected& p0 = draw.P[0];
  const Sample at_corner = draw.sample_at(p0.x, p0.y, 0);
  EXPECT_NEAR((at_corner.base - Vec3(255, 0, 0)).norm(), 0.0, 1e-9);
  const Projected& p1 = draw.P[1];
  const Projected& p2 = draw.P[2];
  const Sample centre = draw.sample_at((p0.x + p1.x + p2.x) / 3, (p0.y + p1.y + p2.y) / 3, 0);
  EXPECT_NEAR((centre.base - Vec3(85, 85, 85)).norm(), 0.0, 1e-9);
  // Flat: the face's normal (+y for this back face), turned towards the viewer (−y).
  EXPECT_NEAR((centre.n - Vec3(0, -1, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(draw.lit(centre, 0), scale_rgb(shade(centre.base, centre.n, false, draw.light, style)));
  EXPECT_EQ(draw.shade_sample(50, 50, 0), draw.lit(draw.sample_at(50.5, 50.5, 0), 0));
}

}  // namespace
}  // namespace breastfit::render::detail
