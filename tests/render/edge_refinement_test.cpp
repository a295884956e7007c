// The adaptive path's marks on tiny synthetic grids, the marked pixels' slots and box counts, and
// the path against the full supersampled one on a small scene.
#include "breastfit/render/detail/edge_refinement.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "breastfit/render/detail/supersampled_surface.h"
#include "render/render_test_camera.h"

namespace breastfit::render::detail {
namespace {

/// A width × height grid of pixel centres, every pixel won by `winner(x, y)` (−1: none) at
/// `depth(x, y)`.
template <class Winner, class Depth>
PixelCentres centres(int width, int height, Winner&& winner, Depth&& depth) {
  PixelCentres c{width, height, std::vector<float>(static_cast<size_t>(width) * height, kEmpty),
                 std::vector<std::int32_t>(static_cast<size_t>(width) * height, -1), {}};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::int32_t t = winner(x, y);
      if (t < 0) continue;
      c.winner[static_cast<size_t>(y) * width + x] = t;
      c.depth[static_cast<size_t>(y) * width + x] = depth(x, y);
      c.won.add({x, x}, {y, y});
    }
  return c;
}

/// The marks as rows of '#' (marked) and '.'.
std::vector<std::string> picture(const std::vector<std::uint8_t>& mark, int width) {
  std::vector<std::string> rows;
  for (size_t p = 0; p < mark.size(); ++p) {
    if (p % width == 0) rows.emplace_back();
    rows.back() += mark[p] ? '#' : '.';
  }
  return rows;
}

TEST(EdgeRefinement, MarksBothSidesOfACoverageChange) {
  // A 3 × 3 block of one triangle: its border and the ring around it, not its centre.
  const PixelCentres c = centres(
      7, 6, [](int x, int y) { return x >= 1 && x <= 3 && y >= 1 && y <= 3 ? 0 : -1; }, [](int, int) { return 1.0f; });
  const std::vector<std::string> expected = {"#####..", "#####..", "##.##..", "#####..", "#####..", "......."};
  EXPECT_EQ(picture(mark_edges(c, {1}, 5.0), 7), expected);
}

TEST(EdgeRefinement, MarksAChangeOfFacingButNotOfTriangle) {
  // Columns 0-1: triangle 0, column 2: triangle 1, columns 3-4: triangle 2, all at one depth.
  auto winner = [](int x, int) { return x < 2 ? 0 : x < 3 ? 1 : 2; };
  const PixelCentres c = centres(5, 3, winner, [](int, int) { return 1.0f; });
  // 0 and 1 face the camera, 2 does not: only the columns next to the 1 | 2 change are marked.
  EXPECT_EQ(picture(mark_edges(c, {1, 1, 0}, 5.0), 5), (std::vector<std::string>{"..##.", "..##.", "..##."}));
  EXPECT_EQ(picture(mark_edges(c, {1, 1, 1}, 5.0), 5), (std::vector<std::string>{".....", ".....", "....."}));
}

TEST(EdgeRefinement, MarksDepthJumpsBeyondTheEdgeDepth) {
  // One triangle, a step of depth 10 between rows 1 and 2.
  const PixelCentres c = centres(4, 4, [](int, int) { return 0; }, [](int, int y) { return y < 2 ? 0.0f : 10.0f; });
  EXPECT_EQ(picture(mark_edges(c, {1}, 9.5), 4), (std::vector<std::string>{"....", "####", "####", "...."}));
  EXPECT_EQ(picture(mark_edges(c, {1}, 10.5), 4), (std::vector<std::string>{"....", "....", "....", "...."}));
}

TEST(EdgeRefinement, MarksNothingWhenNothingIsWon) {
  const PixelCentres c = centres(3, 3, [](int, int) { return -1; }, [](int, int) { return 0.0f; });
  EXPECT_EQ(mark_edges(c, {}, 1.0), std::vector<std::uint8_t>(9, 0));
}

TEST(EdgeRefinement, MarkedPixelsAreNumberedInRasterOrderAndCountedInBoxes) {
  const int width = 5, height = 4;
  const std::vector<std::uint8_t> mark = {0, 1, 0, 0, 0,  //
                                          0, 0, 0, 1, 0,  //
                                          1, 0, 0, 0, 0,  //
                                          0, 0, 0, 0, 1};
  const MarkedPixels marked(mark, width, height);
  EXPECT_EQ(marked.count(), 4);
  std::int32_t next = 0;
  for (size_t p = 0; p < mark.size(); ++p) EXPECT_EQ(marked.slot(p), mark[p] ? next++ : -1) << p;
  for (int y0 = 0; y0 < height; ++y0)
    for (int y1 = y0; y1 < height; ++y1)
      for (int x0 = 0; x0 < width; ++x0)
        for (int x1 = x0; x1 < width; ++x1) {
          bool any = false;
          for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) any = any || mark[static_cast<size_t>(y) * width + x];
          EXPECT_EQ(marked.any_in(x0, y0, x1, y1), any) << x0 << "," << y0 << " " << x1 << "," << y1;
        }
}

// A square turned in the image over a farther one: silhouettes and a depth jump. The adaptive
// path covers the samples the full path covers, at the same depths (to rounding: an unmarked
// pixel's depth is its centre's).
TEST(EdgeRefinement, CoversTheSamplesOfTheFullPath) {
  const Camera camera = test::front_camera(2.0);
  Points V(8, 3);
  V << -0.9, 0.5, -0.9, 0.9, 0.5, -0.9, 0.9, 0.5, 0.9, -0.9, 0.5, 0.9,  // far square (y = 0.5)
      0.0, -0.5, -0.6, 0.6, -0.5, 0.0, 0.0, -0.5, 0.6, -0.6, -0.5, 0.0;   // near, turned by 45°
  Triangles F(4, 3);
  F << 0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7;
  const SurfaceStyle style;
  const int width = 24, height = 24, ss = 2;
  const Points no_normals;
  const Colors no_colours;
  const SurfaceDraw draw(camera, V, F, no_normals, no_colours, style, width * ss, height * ss);
  ASSERT_TRUE(draw.all_fixed);
  auto render = [&](bool adaptive) {
    Image colour(width * ss, height * ss, {255, 255, 255});
    std::vector<float> depth(static_cast<size_t>(width * ss) * height * ss, kEmpty);
    SurfaceTarget target{colour, depth, width * ss, height * ss, width, height, ss};
    if (adaptive)
      draw_edge_refined(draw, target);
    else
      draw_supersampled(draw, target);
    return depth;
  };
  const std::vector<float> adaptive = render(true), full = render(false);
  int covered = 0;
  for (size_t i = 0; i < full.size(); ++i) {
    covered += full[i] < kEmpty;
    ASSERT_EQ(adaptive[i] < kEmpty, full[i] < kEmpty) << i;
    if (full[i] < kEmpty) {
      EXPECT_NEAR(adaptive[i], full[i], 1e-4) << i;
    }
  }
  EXPECT_GT(covered, 1000);
  EXPECT_LT(covered, static_cast<int>(full.size()));
}

}  // namespace
}  // namespace breastfit::render::detail
