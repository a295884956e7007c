// The rasterizer's triangle setup: pixel spans, edge functions and depth planes, the fixed-point
// edge functions (either winding, no cracks along a shared edge) and the pass-1 box loop.
#include "breastfit/render/detail/raster_setup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace breastfit::render::detail {
namespace {

bool empty(Span s) { return s.lo > s.hi; }

TEST(RasterSetup, PixelSpanHoldsTheCentresInside) {
  EXPECT_EQ(pixel_span(0.4, 2.6, 10).lo, 0);
  EXPECT_EQ(pixel_span(0.4, 2.6, 10).hi, 2);
  EXPECT_EQ(pixel_span(0.5, 2.5, 10).lo, 0);  // centres on the bounds are inside
  EXPECT_EQ(pixel_span(0.5, 2.5, 10).hi, 2);
  EXPECT_TRUE(empty(pixel_span(0.6, 1.4, 10)));  // between two centres
  EXPECT_EQ(pixel_span(-5.0, 100.0, 10).lo, 0);  // clipped
  EXPECT_EQ(pixel_span(-5.0, 100.0, 10).hi, 9);
  EXPECT_TRUE(empty(pixel_span(std::nan(""), 3.0, 10)));
  EXPECT_TRUE(empty(pixel_span(0.0, std::numeric_limits<double>::infinity(), 10)));
}

TEST(RasterSetup, PixelIndexSaturates) {
  EXPECT_EQ(pixel_index(2.7), 2);
  EXPECT_EQ(pixel_index(-0.5), -1);
  EXPECT_EQ(pixel_index(-1e30), -1);
  EXPECT_EQ(pixel_index(1e30), 1073741824);
  EXPECT_EQ(pixel_index(std::nan("")), -1);
}

TEST(RasterSetup, BoxGrowsToHoldItsSpans) {
  Box box;
  EXPECT_TRUE(box.empty());
  box.add({3, 5}, {2, 2});
  box.add({1, 4}, {6, 7});
  EXPECT_FALSE(box.empty());
  EXPECT_EQ(box.x0, 1);
  EXPECT_EQ(box.x1, 5);
  EXPECT_EQ(box.y0, 2);
  EXPECT_EQ(box.y1, 7);
}

TEST(RasterSetup, TrianglePlanesAreBarycentricsAndDepth) {
  const Projected p0{1, 1, 10}, p1{9, 2, 20}, p2{3, 8, 40};
  const TrianglePlanes planes = triangle_planes(p0, p1, p2, edge(p0, p1, p2.x, p2.y));
  for (const Projected& p : {p0, p1, p2}) {
    const double b0 = planes.e0.at(p.x, p.y), b1 = planes.e1.at(p.x, p.y), b2 = planes.e2.at(p.x, p.y);
    EXPECT_NEAR(b0 + b1 + b2, 1.0, 1e-12);
    EXPECT_NEAR(planes.depth.at(p.x, p.y), p.depth, 1e-9);
  }
  EXPECT_NEAR(planes.e0.at(p0.x, p0.y), 1.0, 1e-12);
  EXPECT_NEAR(planes.e1.at(p1.x, p1.y), 1.0, 1e-12);
  EXPECT_NEAR(planes.e2.at(p2.x, p2.y), 1.0, 1e-12);
  const double cx = (p0.x + p1.x + p2.x) / 3, cy = (p0.y + p1.y + p2.y) / 3;
  EXPECT_NEAR(planes.depth.at(cx, cy), (10.0 + 20.0 + 40.0) / 3, 1e-9);
}

/// The samples of an n × n grid inside the triangle by its fixed-point edge functions.
std::vector<bool> fixed_cover(const Projected& p0, const Projected& p1, const Projected& p2, int n) {
  std::vector<bool> inside(static_cast<size_t>(n) * n, false);
  const auto g = fixed_edges(p0, p1, p2, sample_centre(0), sample_centre(0), kSampleStep);
  if (!g) return inside;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      inside[static_cast<size_t>(y) * n + x] = g->g0.at(x, y) >= 0 && g->g1.at(x, y) >= 0 && g->g2.at(x, y) >= 0;
  return inside;
}

TEST(RasterSetup, FixedEdgesArePositiveInsideWhicheverTheWinding) {
  const Projected a{1.2, 0.7, 0}, b{9.6, 2.1, 0}, c{3.3, 8.9, 0};
  const std::vector<bool> ccw = fixed_cover(a, b, c, 12), cw = fixed_cover(a, c, b, 12);
  EXPECT_EQ(ccw, cw);
  int n = 0;
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const double e0 = edge(b, c, px, py), e1 = edge(c, a, px, py), e2 = edge(a, b, px, py);
      const bool strictly_in = (e0 > 0.1 && e1 > 0.1 && e2 > 0.1) || (e0 < -0.1 && e1 < -0.1 && e2 < -0.1);
      const bool clearly_out = (e0 < -0.1 || e1 < -0.1 || e2 < -0.1) && (e0 > 0.1 || e1 > 0.1 || e2 > 0.1);
      if (strictly_in || clearly_out) {
        EXPECT_EQ(ccw[static_cast<size_t>(y) * 12 + x], strictly_in) << x << "," << y;
      }
      n += ccw[static_cast<size_t>(y) * 12 + x];
    }
  EXPECT_GT(n, 20);
}

TEST(RasterSetup, TrianglesSharingAnEdgeLeaveNoCrack) {
  // A square split along a diagonal through sample centres: every sample of the square is in one
  // triangle or both (those on the diagonal).
  const Projected a{0.5, 0.5, 0}, b{8.5, 0.5, 0}, c{8.5, 8.5, 0}, d{0.5, 8.5, 0};
  const std::vector<bool> upper = fixed_cover(a, b, c, 10), lower = fixed_cover(a, c, d, 10);
  for (int y = 0; y <= 8; ++y)
    for (int x = 0; x <= 8; ++x) {
      const size_t i = static_cast<size_t>(y) * 10 + x;
      EXPECT_TRUE(upper[i] || lower[i]) << x << "," << y;
      EXPECT_EQ(upper[i] && lower[i], x == y) << x << "," << y;
    }
}

TEST(RasterSetup, FixedEdgesOfADegenerateTriangleAreNone) {
  EXPECT_FALSE(fixed_edges({0, 0, 0}, {4, 4, 0}, {8, 8, 0}, 0, 0, kSampleStep).has_value());
  EXPECT_FALSE(fixed_edges({1, 1, 0}, {1.0001, 1, 0}, {1, 1.0001, 0}, 0, 0, kSampleStep).has_value());  // < 1/256
  EXPECT_TRUE(fixed_edges({1, 1, 0}, {1.01, 1, 0}, {1, 1.01, 0}, 0, 0, kSampleStep).has_value());
  EXPECT_TRUE(fixed_range({4e6, -4e6, 0}));
  EXPECT_FALSE(fixed_range({5e6, 0, 0}));
}

TEST(RasterSetup, FillBoxWritesTheNearerSamples) {
  const int w = 8;
  std::vector<float> depth(static_cast<size_t>(w) * w, kEmpty);
  std::vector<std::int32_t> winner(depth.size(), -1);
  auto fill = [&](const Projected& p0, const Projected& p1, const Projected& p2, std::int32_t t) {
    const Span xs = pixel_span(0, w, w), ys = pixel_span(0, w, w);
    const auto g = fixed_edges(p0, p1, p2, sample_centre(xs.lo), sample_centre(ys.lo), kSampleStep);
    const Linear ez = triangle_planes(p0, p1, p2, edge(p0, p1, p2.x, p2.y)).depth;
    return fill_box(g->g0, g->g1, g->g2, xs, ys, ez, 1, depth.data(), winner.data(), w, t);
  };
  // Two triangles covering the whole grid at depth 5, then one at depth 7 (behind: nothing
  // written), then one at depth 3 over the lower left half.
  EXPECT_TRUE(fill({0, 0, 5}, {8, 0, 5}, {8, 8, 5}, 0));
  EXPECT_TRUE(fill({0, 0, 5}, {8, 8, 5}, {0, 8, 5}, 1));
  EXPECT_FALSE(fill({0, 0, 7}, {8, 0, 7}, {0, 8, 7}, 2));
  EXPECT_TRUE(fill({0, 0, 3}, {8, 8, 3}, {0, 8, 3}, 3));
  for (int y = 0; y < w; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      const std::int32_t expected = x <= y ? 3 : 0;  // equal depths: the first drawn wins
      EXPECT_EQ(winner[i], expected) << x << "," << y;
      EXPECT_FLOAT_EQ(depth[i], expected == 3 ? 3.0f : 5.0f);
    }
  // A box sampled at (scale · (x + 0.5), scale · (y + 0.5)): the depth plane at those points.
  std::vector<float> coarse(4, kEmpty);
  std::vector<std::int32_t> coarse_winner(4, -1);
  const Projected q0{0, 0, 0}, q1{8, 0, 8}, q2{0, 8, 0};  // depth = x
  const std::int64_t step = 4 * kSampleStep;
  const auto g = fixed_edges(q0, q1, q2, 2 * kSampleStep, 2 * kSampleStep, step);
  const Linear ez = triangle_planes(q0, q1, q2, edge(q0, q1, q2.x, q2.y)).depth;
  EXPECT_TRUE(fill_box(g->g0, g->g1, g->g2, {0, 1}, {0, 1}, ez, 4, coarse.data(), coarse_winner.data(), 2, 9));
  EXPECT_EQ(coarse_winner, (std::vector<std::int32_t>{9, 9, 9, -1}));  // (6, 6) is outside
  EXPECT_NEAR(coarse[0], 2.0f, 1e-5);
  EXPECT_NEAR(coarse[1], 6.0f, 1e-5);
  EXPECT_NEAR(coarse[2], 2.0f, 1e-5);
}

}  // namespace
}  // namespace breastfit::render::detail
