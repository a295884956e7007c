// The full surface path: drawn over what the buffers hold (depth-tested against it), and a pixel
// lit once where one smooth patch covers it, sample by sample at an edge.
#include "breastfit/render/detail/supersampled_surface.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "render/render_test_camera.h"

namespace breastfit::render::detail {
namespace {

/// A square facing the camera at depth y over [x0, x1] × [z0, z1].
void square(Points& V, Triangles& F, double x0, double x1, double z0, double z1, double y) {
  V.resize(4, 3);
  V << x0, y, z0, x1, y, z0, x1, y, z1, x0, y, z1;
  F.resize(2, 3);
  F << 0, 1, 2, 0, 2, 3;
}

TEST(SupersampledSurface, DrawsOverTheBuffersWithADepthTest) {
  const int width = 16, height = 16, ss = 2, w = width * ss, h = height * ss;
  const Rgb background{255, 255, 255}, nearer{1, 2, 3};
  Image colour(w, h, background);
  std::vector<float> depth(static_cast<size_t>(w) * h, kEmpty);
  // Something at depth 49 (nearer than the square at y = 0: depth 50) in the left half.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w / 2; ++x) {
      depth[static_cast<size_t>(y) * w + x] = 49.0f;
      colour.set(x, y, nearer);
    }
  Points V;
  Triangles F;
  square(V, F, -0.5, 0.5, -0.5, 0.5, 0.0);
  SurfaceStyle style;
  style.smooth = false;
  const Camera camera = test::front_camera(2.0);
  const Points no_normals;
  const Colors no_colours;
  const SurfaceDraw draw(camera, V, F, no_normals, no_colours, style, w, h);
  SurfaceTarget target{colour, depth, w, h, width, height, ss};
  draw_supersampled(draw, target);
  // The square covers samples [8, 23] each way: its right half drawn at depth 50, its left half
  // behind what was there.
  int drawn = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float d = depth[static_cast<size_t>(y) * w + x];
      const bool in_square = x >= 8 && x <= 23 && y >= 8 && y <= 23;
      if (x < w / 2) {
        EXPECT_EQ(d, 49.0f);
        EXPECT_EQ(colour.at(x, y), nearer);
      } else if (in_square) {
        EXPECT_NEAR(d, 50.0f, 1e-4);
        EXPECT_EQ(colour.at(x, y), draw.shade_sample(x, y, 0)) << x << "," << y;  // flat: one colour
        ++drawn;
      } else {
        EXPECT_EQ(d, kEmpty);
        EXPECT_EQ(colour.at(x, y), background);
      }
    }
  EXPECT_EQ(drawn, 8 * 16);
}

}  // namespace
}  // namespace breastfit::render::detail
