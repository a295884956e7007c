#include "breastfit/render/detail/supersampled_surface.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "breastfit/render/detail/block_far.h"
#include "breastfit/render/detail/raster_setup.h"

namespace breastfit::render::detail {

namespace {

/// Depths of one output pixel's samples within kFlatPixels output pixels of each other: the
/// surface does not jump (no silhouette or fold) inside it.
constexpr double kFlatPixels = 2.0;

/// Pass 1 of one triangle in floating point (perspective views, or corners beyond the fixed-point
/// range) over its box xs × ys of a buffer `w` samples wide: where it covers a sample nearer than
/// `depth`, its depth (perspective-correct) and the winner `t` are written. True when any sample was.
bool fill_box_float(const Projected& p0, const Projected& p1, const Projected& p2, double area, bool perspective,
                    Span xs, Span ys, float* depth_buffer, std::int32_t* winner, int w, std::int32_t t) {
  const double w0 = perspective ? 1.0 / p0.depth : 1.0;
  const double w1 = perspective ? 1.0 / p1.depth : 1.0;
  const double w2 = perspective ? 1.0 / p2.depth : 1.0;
  // The edge functions are linear in the pixel position: step them along each row.
  const TrianglePlanes planes = triangle_planes(p0, p1, p2, area);
  const Linear &e0 = planes.e0, &e1 = planes.e1, &e2 = planes.e2;
  const Linear& ez = planes.depth;  // orthographic: the depth is linear in the pixel position too
  const Linear* edges[3] = {&e0, &e1, &e2};
  // Where each edge function crosses zero along a row: −a / dx, by a reciprocal taken once per
  // triangle (the one-sample widening below absorbs its rounding).
  const double inv_dx[3] = {e0.dx != 0 ? 1.0 / e0.dx : 0.0, e1.dx != 0 ? 1.0 / e1.dx : 0.0,
                            e2.dx != 0 ? 1.0 / e2.dx : 0.0};
  bool wrote = false;
  for (int y = ys.lo; y <= ys.hi; ++y) {
    const double py = y + 0.5;
    const double x_start = xs.lo + 0.5;
    // The samples of this row inside all three edges, from where each edge function crosses
    // zero, one sample wider on each side for rounding (the exact test below decides).
    int n_lo = 0, n_hi = xs.hi - xs.lo;
    for (int j = 0; j < 3; ++j) {
      const Linear* e = edges[j];
      const double a = e->at(x_start, py);
      if (e->dx > 0) {
        if (a < 0) n_lo = std::max(n_lo, static_cast<int>(std::min(-a * inv_dx[j], 1e9)) - 1);  // -a / dx > 0
      } else if (e->dx < 0) {
        n_hi = std::min(n_hi, static_cast<int>(std::clamp(-a * inv_dx[j], -1e9, 1e9)) + 1);
      } else if (a < 0) {
        n_hi = -1;
      }
    }
    if (n_lo > n_hi) continue;
    const double x_first = x_start + n_lo;
    double a0 = e0.at(x_first, py), a1 = e1.at(x_first, py), a2 = e2.at(x_first, py), az = ez.at(x_first, py);
    for (int x = xs.lo + n_lo; x <= xs.lo + n_hi; ++x, a0 += e0.dx, a1 += e1.dx, a2 += e2.dx, az += ez.dx) {
      double b0 = a0, b1 = a1, b2 = a2;
      if (b0 < 0 || b1 < 0 || b2 < 0) continue;
      double depth = az;
      if (perspective) {  // perspective-correct barycentrics
        b0 *= w0;
        b1 *= w1;
        b2 *= w2;
        const double sum = b0 + b1 + b2;
        depth = (b0 * p0.depth + b1 * p1.depth + b2 * p2.depth) / sum;
      }
      const size_t idx = static_cast<size_t>(y) * w + x;
      if (!(depth < depth_buffer[idx])) continue;
      depth_buffer[idx] = static_cast<float>(depth);
      winner[idx] = t;
      wrote = true;
    }
  }
  return wrote;
}

/// Pass 1 of one triangle (corners p) over its box xs × ys of the target's samples.
bool fill_triangle(const SurfaceDraw& draw, const std::array<Projected, 3>& p, std::int32_t t, Span xs, Span ys,
                   SurfaceTarget& target, std::int32_t* winner) {
  const double area = draw.area[static_cast<size_t>(t)];
  if (!draw.perspective && fixed_range(p[0]) && fixed_range(p[1]) && fixed_range(p[2])) {
    // Orthographic: exact integer edge functions over the triangle's box, the depth linear in
    // the sample position (one multiply-add per sample instead of a perspective division).
    const auto g = fixed_edges(p[0], p[1], p[2], sample_centre(xs.lo), sample_centre(ys.lo), kSampleStep);
    if (!g) return false;  // thinner than a 256th of a sample
    const Linear ez = triangle_planes(p[0], p[1], p[2], area).depth;
    return fill_box(g->g0, g->g1, g->g2, xs, ys, ez, 1, target.depth.data(), winner, target.w, t);
  }
  return fill_box_float(p[0], p[1], p[2], area, draw.perspective, xs, ys, target.depth.data(), winner, target.w, t);
}

/// Pass 1's result: each sample's nearest triangle of this call (−1: none) and a box around the
/// samples won, which pass 2 visits (conservative: it skips the samples nobody won).
struct Winners {
  std::vector<std::int32_t> winner;
  Box box;
};

Winners nearest_triangles(const SurfaceDraw& draw, SurfaceTarget& target) {
  Winners won{std::vector<std::int32_t>(static_cast<size_t>(target.w) * target.h, -1), {}};
  BlockFar block_far(target.w, target.h);  // the coarse depth test of the back faces
  CornerStream corners(draw);
  for (size_t k = 0; k < draw.order.size(); ++k) {
    if (k == draw.n_front) block_far.fill([&](size_t p) { return target.depth[p]; });
    const std::array<Projected, 3>& c = corners.at(k);
    const Projected &p0 = c[0], &p1 = c[1], &p2 = c[2];
    const Span xs = pixel_span(std::min({p0.x, p1.x, p2.x}), std::max({p0.x, p1.x, p2.x}), target.w);
    const Span ys = pixel_span(std::min({p0.y, p1.y, p2.y}), std::max({p0.y, p1.y, p2.y}), target.h);
    if (xs.lo > xs.hi || ys.lo > ys.hi) continue;
    // Every depth inside the triangle (perspective-correct too) lies between its corners'.
    if (k >= draw.n_front && block_far.hidden(xs.lo, ys.lo, xs.hi, ys.hi, std::min({p0.depth, p1.depth, p2.depth})))
      continue;
    if (fill_triangle(draw, c, draw.order[k], xs, ys, target, won.winner.data())) won.box.add(xs, ys);
  }
  return won;
}

/// How the ss × ss samples of the output pixel whose first sample is (x0, y0) are covered: flat
/// when they all show this call's surface, facing the same way and within kFlatPixels output
/// pixels of depth of each other (not across a silhouette); by one triangle or several.
struct PixelCover {
  bool flat = false;
  bool one_triangle = true;
};

PixelCover pixel_cover(const SurfaceDraw& draw, const std::vector<std::int32_t>& winner, const SurfaceTarget& target,
                       int x0, int y0, double flat_depth_ortho) {
  const int ss = target.ss, w = target.w;
  const std::int32_t t0 = winner[static_cast<size_t>(y0) * w + x0];
  PixelCover cover{t0 >= 0 && ss > 1, true};
  if (!cover.flat) return cover;
  const std::uint8_t front = draw.front[static_cast<size_t>(t0)];
  float lo = target.depth[static_cast<size_t>(y0) * w + x0], hi = lo;
  for (int dy = 0; dy < ss && cover.flat; ++dy)
    for (int dx = 0; dx < ss && cover.flat; ++dx) {
      const size_t idx = static_cast<size_t>(y0 + dy) * w + x0 + dx;
      cover.flat = winner[idx] >= 0 && draw.front[static_cast<size_t>(winner[idx])] == front;
      cover.one_triangle = cover.one_triangle && winner[idx] == t0;
      lo = std::min(lo, target.depth[idx]);
      hi = std::max(hi, target.depth[idx]);
    }
  cover.flat = cover.flat && hi - lo <= (draw.perspective ? kFlatPixels * draw.camera.world_per_pixel(lo, target.height)
                                                          : flat_depth_ortho);
  return cover;
}

/// The colour of a flat output pixel whose first sample is (x0, y0): lit once with its samples'
/// mean normal and colour, which for the small variations inside one pixel is their mean shade to
/// within a grey level (when one triangle covers the whole pixel: its normal and colour at the
/// pixel's centre, their mean up to the normalisation).
Rgb flat_pixel_colour(const SurfaceDraw& draw, const std::vector<std::int32_t>& winner, const SurfaceTarget& target,
                      int x0, int y0, bool one_triangle) {
  const int ss = target.ss, w = target.w;
  const std::int32_t t0 = winner[static_cast<size_t>(y0) * w + x0];
  Sample mean{Vec3::Zero(), Vec3::Zero()};
  if (one_triangle) {
    mean = draw.sample_at_pixel(x0, y0, ss, t0);
    mean.base *= ss * ss;
  } else {
    // The pixel's triangles (the small triangles of a dense scan: two or three a pixel), each
    // sampled once at the mean of its samples' positions and weighted by their number: the
    // interpolated normal and colour are linear in the position, so this is their mean but for
    // the normalisation of the normal, well below a grey level within one pixel.
    std::array<std::int32_t, 16> tris;
    std::array<int, 16> count{};
    std::array<double, 16> sum_x{}, sum_y{};
    int distinct = 0;
    for (int dy = 0; dy < ss; ++dy)
      for (int dx = 0; dx < ss; ++dx) {
        const std::int32_t t = winner[static_cast<size_t>(y0 + dy) * w + x0 + dx];
        int j = 0;
        while (j < distinct && tris[j] != t) ++j;
        if (j == distinct) tris[distinct++] = t;
        ++count[j];
        sum_x[j] += x0 + dx + 0.5;
        sum_y[j] += y0 + dy + 0.5;
      }
    for (int j = 0; j < distinct; ++j) {
      const Sample s = draw.sample_at(sum_x[j] / count[j], sum_y[j] / count[j], tris[j]);
      mean.n += count[j] * s.n;
      mean.base += count[j] * s.base;
    }
  }
  const double norm = mean.n.norm();
  return norm > 0 ? draw.lit({mean.n / norm, mean.base / (ss * ss)}, t0) : draw.shade_sample(x0, y0, t0);
}

/// Pass 2, by output pixel (a block of ss × ss samples) over the box pass 1 won: a flat pixel is
/// lit once (flat_pixel_colour), the others sample by sample (edges stay anti-aliased).
void shade_pixels(const SurfaceDraw& draw, const Winners& won, SurfaceTarget& target) {
  const int ss = target.ss;
  const double flat_depth_ortho = kFlatPixels * draw.camera.world_per_pixel(0.0, target.height);  // any depth
  for (int y0 = won.box.y0 / ss * ss; y0 <= won.box.y1; y0 += ss)
    for (int x0 = won.box.x0 / ss * ss; x0 <= won.box.x1; x0 += ss) {
      const PixelCover cover = pixel_cover(draw, won.winner, target, x0, y0, flat_depth_ortho);
      if (cover.flat) {
        const Rgb c = flat_pixel_colour(draw, won.winner, target, x0, y0, cover.one_triangle);
        for (int dy = 0; dy < ss; ++dy)
          for (int dx = 0; dx < ss; ++dx) target.colour.set(x0 + dx, y0 + dy, c);
        continue;
      }
      for (int y = y0; y < y0 + ss; ++y)
        for (int x = x0; x < x0 + ss; ++x) {
          const std::int32_t t = won.winner[static_cast<size_t>(y) * target.w + x];
          if (t >= 0) target.colour.set(x, y, draw.shade_sample(x, y, t));
        }
    }
}

}  // namespace

void draw_supersampled(const SurfaceDraw& draw, SurfaceTarget& target) {
  const Winners won = nearest_triangles(draw, target);
  shade_pixels(draw, won, target);
}

}  // namespace breastfit::render::detail
