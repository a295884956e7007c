#include "breastfit/render/detail/edge_refinement.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "breastfit/render/detail/block_far.h"

namespace breastfit::render::detail {

namespace {

/// Neighbouring pixels more than this many output pixels apart in depth are at an occluding edge,
/// not the scan's noise or a steep slope (with 2 pixels, a third of a side figure's surface was
/// marked, mostly noise; the silhouette of a steep slope is marked by its coverage).
constexpr double kEdgeDepthPixels = 8.0;

/// `box` grown by one pixel on each side, clipped to the width × height grid.
Box around(const Box& box, int width, int height) {
  Box grown;
  grown.add({std::max(0, box.x0 - 1), std::min(width - 1, box.x1 + 1)},
            {std::max(0, box.y0 - 1), std::min(height - 1, box.y1 + 1)});
  return grown;
}

/// Where the refinement looks for each triangle: per bucket, a box (in samples) around its
/// triangles, to skip the buckets that reach no marked pixel; per triangle (in drawing order),
/// its box of samples (x0 > x1: no sample), to read the corners of only the triangles that reach
/// a marked pixel.
struct SampleBoxes {
  std::vector<Box> bucket;
  std::vector<std::array<std::uint16_t, 4>> triangle;
};

/// The centre pass and, gathered on the way, the refinement's boxes.
struct CentrePass {
  PixelCentres centres;
  SampleBoxes boxes;
};

/// Pass 1 at one sample per output pixel.
CentrePass centre_pass(const SurfaceDraw& draw, const SurfaceTarget& target) {
  const int W = target.width, H = target.height, ss = target.ss;
  const size_t n_pixels = static_cast<size_t>(W) * H;
  const size_t n_buckets = 2 * static_cast<size_t>(draw.tiles);
  CentrePass pass{{W, H, std::vector<float>(n_pixels, kEmpty), std::vector<std::int32_t>(n_pixels, -1), {}},
                  {std::vector<Box>(n_buckets), std::vector<std::array<std::uint16_t, 4>>(draw.order.size(), {1, 0, 0, 0})}};
  PixelCentres& c = pass.centres;
  BlockFar far(W, H);  // the coarse depth test of the back faces, by blocks of output pixels
  // An output pixel's centre in fixed-point samples, and the step between two.
  const std::int64_t step = static_cast<std::int64_t>(ss) << kSubpixelBits;
  const std::int64_t half = static_cast<std::int64_t>(ss) << (kSubpixelBits - 1);
  CornerStream corners(draw);
  size_t k = 0;
  for (size_t b = 0; b < n_buckets; ++b) {
    if (b == static_cast<size_t>(draw.tiles)) far.fill([&](size_t p) { return c.depth[p]; });
    for (const size_t end = static_cast<size_t>(draw.bucket_end[b]); k < end; ++k) {
      const std::int32_t t = draw.order[k];
      const std::array<Projected, 3>& corner = corners.at(k);
      const Projected &p0 = corner[0], &p1 = corner[1], &p2 = corner[2];
      const double min_x = std::min({p0.x, p1.x, p2.x}), max_x = std::max({p0.x, p1.x, p2.x});
      const double min_y = std::min({p0.y, p1.y, p2.y}), max_y = std::max({p0.y, p1.y, p2.y});
      const Span hx = pixel_span(min_x, max_x, target.w), hy = pixel_span(min_y, max_y, target.h);
      if (hx.lo <= hx.hi && hy.lo <= hy.hi) {  // (a triangle can hold a pixel's centre and no sample's)
        pass.boxes.bucket[b].add(hx, hy);
        pass.boxes.triangle[k] = {static_cast<std::uint16_t>(hx.lo), static_cast<std::uint16_t>(hy.lo),
                                  static_cast<std::uint16_t>(hx.hi), static_cast<std::uint16_t>(hy.hi)};
      }
      const Span xs = pixel_span(min_x / ss, max_x / ss, W), ys = pixel_span(min_y / ss, max_y / ss, H);
      if (xs.lo > xs.hi || ys.lo > ys.hi) continue;
      if (k >= draw.n_front && far.hidden(xs.lo, ys.lo, xs.hi, ys.hi, std::min({p0.depth, p1.depth, p2.depth}))) continue;
      const auto g = fixed_edges(p0, p1, p2, xs.lo * step + half, ys.lo * step + half, step);
      if (!g) continue;
      const Linear ez = triangle_planes(p0, p1, p2, draw.area[static_cast<size_t>(t)]).depth;
      if (fill_box(g->g0, g->g1, g->g2, xs, ys, ez, ss, c.depth.data(), c.winner.data(), W, t)) c.won.add(xs, ys);
    }
  }
  return pass;
}

/// Pass 1 again at the marked pixels' ss × ss samples: sample (dx, dy) of the pixel in slot s
/// at [s · ss² + dy · ss + dx].
struct RefinedSamples {
  std::vector<float> depth;
  std::vector<std::int32_t> winner;
};

/// Pass 1 of triangle t (its fixed-point edge functions g from the sample (sx0, sy0), its depth
/// plane ez) over the samples of the marked pixels in q (output pixels).
void refine_triangle(const FixedEdges& g, const Linear& ez, const Box& q, int sx0, int sy0, const MarkedPixels& marked,
                     int width, int ss, RefinedSamples& refined, std::int32_t t) {
  const int s2 = ss * ss;
  for (int ly = q.y0; ly <= q.y1; ++ly)
    for (int lx = q.x0; lx <= q.x1; ++lx) {
      const std::int32_t s = marked.slot(static_cast<size_t>(ly) * width + lx);
      if (s < 0) continue;
      for (int dy = 0; dy < ss; ++dy) {
        const int y = ly * ss + dy;
        const std::int64_t oy = y - sy0;
        for (int dx = 0; dx < ss; ++dx) {
          const int x = lx * ss + dx;
          const std::int64_t ox = x - sx0;
          if ((g.g0.at(ox, oy) | g.g1.at(ox, oy) | g.g2.at(ox, oy)) < 0) continue;
          const double depth = ez.at(x + 0.5, y + 0.5);
          const size_t j = static_cast<size_t>(s) * s2 + dy * ss + dx;
          if (!(depth < refined.depth[j])) continue;
          refined.depth[j] = static_cast<float>(depth);
          refined.winner[j] = t;
        }
      }
    }
}

/// The refinement: the buckets, then the triangles, whose boxes reach a marked pixel.
RefinedSamples refine_marked(const SurfaceDraw& draw, const SurfaceTarget& target, const CentrePass& pass,
                             const MarkedPixels& marked) {
  const int W = target.width, ss = target.ss, s2 = ss * ss;
  RefinedSamples refined{std::vector<float>(static_cast<size_t>(marked.count()) * s2, kEmpty),
                         std::vector<std::int32_t>(static_cast<size_t>(marked.count()) * s2, -1)};
  BlockFar far(W, target.height);  // as in the centre pass, with the refined depths
  const size_t n_buckets = 2 * static_cast<size_t>(draw.tiles);
  size_t k = 0;
  for (size_t b = 0; b < n_buckets; ++b) {
    const size_t begin = k, end = static_cast<size_t>(draw.bucket_end[b]);
    k = end;
    if (marked.count() == 0) break;
    if (b == static_cast<size_t>(draw.tiles))  // a marked pixel's farthest sample, an unmarked pixel's depth
      far.fill([&](size_t p) {
        const std::int32_t s = marked.slot(p);
        if (s < 0) return pass.centres.depth[p];
        float farthest = 0.0f;
        for (int j = 0; j < s2; ++j) farthest = std::max(farthest, refined.depth[static_cast<size_t>(s) * s2 + j]);
        return farthest;
      });
    const Box& box = pass.boxes.bucket[b];
    if (begin == end || box.empty() || !marked.any_in(box.x0 / ss, box.y0 / ss, box.x1 / ss, box.y1 / ss)) continue;
    for (size_t kk = begin; kk < end; ++kk) {
      const std::array<std::uint16_t, 4>& tb = pass.boxes.triangle[kk];
      if (tb[0] > tb[2]) continue;
      Box q;  // the triangle's box in output pixels
      q.add({tb[0] / ss, tb[2] / ss}, {tb[1] / ss, tb[3] / ss});
      if (!marked.any_in(q.x0, q.y0, q.x1, q.y1)) continue;
      const std::int32_t t = draw.order[kk];
      const Projected &p0 = draw.P[draw.F(t, 0)], &p1 = draw.P[draw.F(t, 1)], &p2 = draw.P[draw.F(t, 2)];
      if (kk >= draw.n_front && far.hidden(q.x0, q.y0, q.x1, q.y1, std::min({p0.depth, p1.depth, p2.depth}))) continue;
      const int sx0 = q.x0 * ss, sy0 = q.y0 * ss;  // the samples' origin
      const auto g = fixed_edges(p0, p1, p2, sample_centre(sx0), sample_centre(sy0), kSampleStep);
      if (!g) continue;
      const Linear ez = triangle_planes(p0, p1, p2, draw.area[static_cast<size_t>(t)]).depth;
      refine_triangle(*g, ez, q, sx0, sy0, marked, W, ss, refined, t);
    }
  }
  return refined;
}

/// Pass 2 of an unmarked output pixel (its first sample (x0, y0)): lit once at its centre, its
/// colour and depth in all its samples.
void shade_unmarked(const SurfaceDraw& draw, std::int32_t t, float depth, int x0, int y0, SurfaceTarget& target) {
  const int ss = target.ss;
  const Rgb c = draw.lit(draw.sample_at_pixel(x0, y0, ss, t), t);
  for (int dy = 0; dy < ss; ++dy)
    for (int dx = 0; dx < ss; ++dx) {
      target.colour.set(x0 + dx, y0 + dy, c);
      target.depth[static_cast<size_t>(y0 + dy) * target.w + x0 + dx] = depth;
    }
}

/// Pass 2 of a marked output pixel (its first sample (x0, y0)) from its refined samples' winners
/// ws and depths ds: sample by sample, or lit once at its centre when one triangle covers it all.
void shade_marked(const SurfaceDraw& draw, const std::int32_t* ws, const float* ds, int x0, int y0,
                  SurfaceTarget& target) {
  const int ss = target.ss, s2 = ss * ss;
  bool one = ws[0] >= 0;
  for (int j = 1; j < s2 && one; ++j) one = ws[j] == ws[0];
  Rgb one_colour{};
  if (one) one_colour = draw.lit(draw.sample_at_pixel(x0, y0, ss, ws[0]), ws[0]);
  for (int dy = 0; dy < ss; ++dy)
    for (int dx = 0; dx < ss; ++dx) {
      const int j = dy * ss + dx;
      if (ws[j] < 0) continue;
      target.colour.set(x0 + dx, y0 + dy, one ? one_colour : draw.shade_sample(x0 + dx, y0 + dy, ws[j]));
      target.depth[static_cast<size_t>(y0 + dy) * target.w + x0 + dx] = ds[j];
    }
}

/// Pass 2 over the pixels that may hold the surface: their samples' colours and depths.
void shade_pixels(const SurfaceDraw& draw, const PixelCentres& centres, const MarkedPixels& marked,
                  const RefinedSamples& refined, SurfaceTarget& target) {
  const int ss = target.ss, s2 = ss * ss;
  const Box range = around(centres.won, centres.width, centres.height);
  for (int ly = range.y0; ly <= range.y1; ++ly)
    for (int lx = range.x0; lx <= range.x1; ++lx) {
      const size_t p = static_cast<size_t>(ly) * centres.width + lx;
      const std::int32_t s = marked.slot(p);
      if (s >= 0) {
        const size_t first = static_cast<size_t>(s) * s2;
        shade_marked(draw, &refined.winner[first], &refined.depth[first], lx * ss, ly * ss, target);
      } else if (centres.winner[p] >= 0) {
        shade_unmarked(draw, centres.winner[p], centres.depth[p], lx * ss, ly * ss, target);
      }
    }
}

}  // namespace

std::vector<std::uint8_t> mark_edges(const PixelCentres& centres, const std::vector<std::uint8_t>& front,
                                     double edge_depth) {
  const int W = centres.width;
  std::vector<std::uint8_t> mark(static_cast<size_t>(W) * centres.height, 0);
  if (centres.won.empty()) return mark;
  auto differ = [&](size_t p, size_t q) {
    const std::int32_t a = centres.winner[p], b = centres.winner[q];
    if ((a < 0) != (b < 0)) return true;
    if (a < 0) return false;
    return front[static_cast<size_t>(a)] != front[static_cast<size_t>(b)] ||
           std::abs(centres.depth[p] - centres.depth[q]) > edge_depth;
  };
  auto pair = [&](size_t p, size_t q) {
    if (differ(p, q)) mark[p] = mark[q] = 1;
  };
  const Box r = around(centres.won, W, centres.height);
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x) {
      const size_t p = static_cast<size_t>(y) * W + x;
      if (x < r.x1) pair(p, p + 1);
      if (y == r.y1) continue;
      pair(p, p + W);
      if (x < r.x1) pair(p, p + W + 1);
      if (x > r.x0) pair(p, p + W - 1);
    }
  return mark;
}

MarkedPixels::MarkedPixels(const std::vector<std::uint8_t>& mark, int width, int height)
    : width_(width),
      slot_(static_cast<size_t>(width) * height, -1),
      sat_(static_cast<size_t>(width + 1) * (height + 1), 0) {
  for (int y = 0; y < height; ++y) {
    std::int32_t row = 0;
    for (int x = 0; x < width; ++x) {
      const size_t p = static_cast<size_t>(y) * width + x;
      if (mark[p]) slot_[p] = count_++;
      row += mark[p] != 0;
      sat_[static_cast<size_t>(y + 1) * (width + 1) + x + 1] = sat_[static_cast<size_t>(y) * (width + 1) + x + 1] + row;
    }
  }
}

void draw_edge_refined(const SurfaceDraw& draw, SurfaceTarget& target) {
  const CentrePass pass = centre_pass(draw, target);
  if (pass.centres.won.empty()) return;  // nothing drawn
  const double edge_depth = kEdgeDepthPixels * draw.camera.world_per_pixel(0.0, target.height);
  const MarkedPixels marked(mark_edges(pass.centres, draw.front, edge_depth), target.width, target.height);
  const RefinedSamples refined = refine_marked(draw, target, pass, marked);
  shade_pixels(draw, pass.centres, marked, refined, target);
}

}  // namespace breastfit::render::detail
