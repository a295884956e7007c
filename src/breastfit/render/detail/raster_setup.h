#pragma once
/// \file The rasterizer's triangle setup (private to the render layer): pixel spans and boxes,
/// edge functions and depth planes in floating point, the fixed-point edge functions that keep
/// shared edges crack-free, and pass 1 of a triangle over its box of samples. Inline: they run
/// per triangle and per sample in the rasterizer's inner loops.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "breastfit/render/camera.h"

namespace breastfit::render::detail {

/// The depth of a sample no surface covers.
inline constexpr float kEmpty = std::numeric_limits<float>::infinity();

/// Pixels whose centres (i + 0.5) lie in [a, b], clipped to [0, n − 1]: [lo, hi], empty when
/// lo > hi (also for non-finite bounds).
struct Span {
  int lo = 1;
  int hi = 0;
};
inline Span pixel_span(double a, double b, int n) {
  if (!(std::isfinite(a) && std::isfinite(b))) return {};
  const double lo = std::max(0.0, std::ceil(a - 0.5));
  const double hi = std::min(n - 1.0, std::floor(b - 0.5));
  if (lo > hi) return {};
  return {static_cast<int>(lo), static_cast<int>(hi)};
}

/// floor(v) as an int, saturated to [−1, 2^30] (non-finite → −1), for inside-the-image tests.
inline int pixel_index(double v) {
  if (!std::isfinite(v)) return -1;
  return static_cast<int>(std::clamp(std::floor(v), -1.0, 1073741824.0));
}

/// The pixels [x0, x1] × [y0, y1]: empty (x1 < 0) until spans are added.
struct Box {
  int x0 = std::numeric_limits<int>::max(), y0 = std::numeric_limits<int>::max();
  int x1 = -1, y1 = -1;
  bool empty() const { return x1 < 0; }
  /// Grows the box to hold the pixels xs × ys (non-empty spans).
  void add(Span xs, Span ys) {
    x0 = std::min(x0, xs.lo);
    y0 = std::min(y0, ys.lo);
    x1 = std::max(x1, xs.hi);
    y1 = std::max(y1, ys.hi);
  }
};

/// Twice the signed area of the triangle (a, b, p) with p = (px, py): > 0 when p lies to the
/// right of a → b in the y-down image.
inline double edge(const Projected& a, const Projected& b, double px, double py) {
  return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
}

/// dx · px + dy · py + c.
struct Linear {
  double dx = 0, dy = 0, c = 0;
  double at(double px, double py) const { return dx * px + dy * py + c; }
};

/// edge(a, b, px, py) · scale as a linear function of the pixel position.
inline Linear edge_function(const Projected& a, const Projected& b, double scale) {
  const double ex = b.x - a.x, ey = b.y - a.y;
  return {-ey * scale, ex * scale, (ey * a.x - ex * a.y) * scale};
}

/// A triangle's barycentric coordinates as linear functions of the pixel position (its edge
/// functions over its signed area, twice) and, orthographic, its depth from them.
struct TrianglePlanes {
  Linear e0, e1, e2, depth;
};
inline TrianglePlanes triangle_planes(const Projected& p0, const Projected& p1, const Projected& p2, double area) {
  const double inv_area = 1.0 / area;
  const Linear e0 = edge_function(p1, p2, inv_area), e1 = edge_function(p2, p0, inv_area),
               e2 = edge_function(p0, p1, inv_area);
  return {e0, e1, e2,
          {e0.dx * p0.depth + e1.dx * p1.depth + e2.dx * p2.depth, e0.dy * p0.depth + e1.dy * p1.depth + e2.dy * p2.depth,
           e0.c * p0.depth + e1.c * p1.depth + e2.c * p2.depth}};
}

/// An image position in fixed point: kSubpixelBits fractional bits of a (supersampled) sample.
/// Edge functions of fixed-point corners are exact integers, so a sample on an edge shared by
/// two triangles is inside both (no cracks, whatever the order of evaluation).
inline constexpr int kSubpixelBits = 8;
inline constexpr double kSubpixel = 1 << kSubpixelBits;
/// Beyond this (in samples) a corner's fixed-point products could overflow: the double path draws it.
inline constexpr double kFixedLimit = 1 << 22;

struct FixedPoint {
  std::int64_t x, y;
};
inline FixedPoint to_fixed(const Projected& p) {
  // Rounded half away from zero, inline (std::llround is a libm call, ~2 % of a layer's time).
  auto round = [](double v) { return static_cast<std::int64_t>(v + (v < 0 ? -0.5 : 0.5)); };
  return {round(p.x * kSubpixel), round(p.y * kSubpixel)};
}
inline bool fixed_range(const Projected& p) { return std::abs(p.x) < kFixedLimit && std::abs(p.y) < kFixedLimit; }

/// edge(a, b, ·) in fixed point as an integer function of the sample position: its value at the
/// box's first sample and its steps by one sample in x and in y.
struct FixedEdge {
  std::int64_t at_origin, step_x, step_y;
  /// The value `ox` samples right of and `oy` below the first sample.
  std::int64_t at(std::int64_t ox, std::int64_t oy) const { return at_origin + ox * step_x + oy * step_y; }
};
/// edge(a, b, ·) · sign at the fixed-point position (px, py), stepping by `step` (fixed point).
inline FixedEdge fixed_edge_at(const FixedPoint& a, const FixedPoint& b, std::int64_t px, std::int64_t py,
                               std::int64_t step, std::int64_t sign) {
  const std::int64_t ex = b.x - a.x, ey = b.y - a.y;
  return {sign * (ex * (py - a.y) - ey * (px - a.x)), sign * (-ey * step), sign * (ex * step)};
}
/// The fixed-point position of sample x's centre (x + 0.5).
inline std::int64_t sample_centre(int x) {
  return (static_cast<std::int64_t>(x) << kSubpixelBits) + (std::int64_t{1} << (kSubpixelBits - 1));
}
/// One sample in fixed point.
inline constexpr std::int64_t kSampleStep = std::int64_t{1} << kSubpixelBits;

/// A triangle's three edge functions in fixed point (g0 opposite corner 0, …), positive inside
/// whichever way it winds, at the fixed-point position (px, py), stepping by `step`; nullopt when
/// it is thinner than a 256th of a sample (nothing to draw).
struct FixedEdges {
  FixedEdge g0, g1, g2;
};
inline std::optional<FixedEdges> fixed_edges(const Projected& p0, const Projected& p1, const Projected& p2,
                                             std::int64_t px, std::int64_t py, std::int64_t step) {
  const FixedPoint f0 = to_fixed(p0), f1 = to_fixed(p1), f2 = to_fixed(p2);
  const std::int64_t fixed_area = (f1.x - f0.x) * (f2.y - f0.y) - (f1.y - f0.y) * (f2.x - f0.x);
  if (fixed_area == 0) return std::nullopt;
  const std::int64_t sign = fixed_area > 0 ? 1 : -1;
  return FixedEdges{fixed_edge_at(f1, f2, px, py, step, sign), fixed_edge_at(f2, f0, px, py, step, sign),
                    fixed_edge_at(f0, f1, px, py, step, sign)};
}

/// Pass 1 of one triangle over its box xs × ys, in a buffer of `w` samples a row whose sample
/// (x, y) lies at (scale · (x + 0.5), scale · (y + 0.5)) in the coordinates of the depth plane `ez`:
/// where the fixed-point edge functions (g0, g1, g2 at the box's first sample) hold it and it is
/// nearer than `depth`, its depth and the winner `t` are written. True when any sample was.
inline bool fill_box(const FixedEdge& g0, const FixedEdge& g1, const FixedEdge& g2, Span xs, Span ys, const Linear& ez,
                     double scale, float* depth, std::int32_t* winner, int w, std::int32_t t) {
  const double ez_dx = ez.dx * scale;
  std::int64_t r0 = g0.at_origin, r1 = g1.at_origin, r2 = g2.at_origin;
  bool wrote = false;
  for (int y = ys.lo; y <= ys.hi; ++y, r0 += g0.step_y, r1 += g1.step_y, r2 += g2.step_y) {
    std::int64_t a0 = r0, a1 = r1, a2 = r2;
    double az = ez.at(scale * (xs.lo + 0.5), scale * (y + 0.5));
    float* depth_row = depth + static_cast<size_t>(y) * w;
    std::int32_t* winner_row = winner + static_cast<size_t>(y) * w;
    for (int x = xs.lo; x <= xs.hi; ++x, a0 += g0.step_x, a1 += g1.step_x, a2 += g2.step_x, az += ez_dx) {
      if ((a0 | a1 | a2) < 0 || !(az < depth_row[x])) continue;
      depth_row[x] = static_cast<float>(az);
      winner_row[x] = t;
      wrote = true;
    }
  }
  return wrote;
}

}  // namespace breastfit::render::detail
