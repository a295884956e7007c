#include "breastfit/render/rasterizer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/adjacency.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/render/detail/block_far.h"
#include "breastfit/render/detail/raster_setup.h"
#include "breastfit/render/detail/shading.h"

namespace breastfit::render {

using detail::BlockFar;
using detail::edge;
using detail::fill_box;
using detail::FixedEdge;
using detail::fixed_edges;
using detail::fixed_range;
using detail::kEmpty;
using detail::kSubpixelBits;
using detail::Lighting;
using detail::Linear;
using detail::make_lighting;
using detail::pixel_index;
using detail::pixel_span;
using detail::sample_centre;
using detail::scale_rgb;
using detail::shade;
using detail::Span;
using detail::to_vec;
using detail::triangle_planes;
using detail::TrianglePlanes;

namespace {

constexpr std::uint32_t kVisibleInk = std::numeric_limits<std::uint32_t>::max();

}  // namespace

void RasterOptions::validate() const {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw InvalidInput("RasterOptions: width and height must be in [1, 16384], got " +
                       std::to_string(width) + "x" + std::to_string(height));
  if (supersample < 1 || supersample > 4)
    throw InvalidInput("RasterOptions: supersample must be in [1, 4], got " + std::to_string(supersample));
  if (!(depth_bias >= 0) || !std::isfinite(depth_bias))
    throw InvalidInput("RasterOptions: depth_bias must be finite and >= 0, got " + std::to_string(depth_bias));
  if (!(hidden_alpha > 0 && hidden_alpha <= 1))
    throw InvalidInput("RasterOptions: hidden_alpha must be in (0, 1], got " + std::to_string(hidden_alpha));
}

Rasterizer::Rasterizer(const Camera& camera, const RasterOptions& options)
    : camera_(camera), options_(options) {
  camera_.validate();
  options_.validate();
  w_ = options_.width * options_.supersample;
  h_ = options_.height * options_.supersample;
  colour_ = Image(w_, h_, options_.background);
  depth_.assign(static_cast<size_t>(w_) * h_, kEmpty);
}

Projected Rasterizer::project_internal(const Vec3& p) const { return camera_.project(p, w_, h_); }

Projected Rasterizer::project(const Vec3& p) const {
  return camera_.project(p, options_.width, options_.height);
}

void Rasterizer::next_call() {
  ++call_id_;
  if (call_id_ == kVisibleInk || call_id_ == 0) call_id_ = 1;
}

void Rasterizer::draw_mesh(const TriangleMesh& mesh, const SurfaceStyle& style) {
  draw_mesh(mesh.V, mesh.F, mesh.N, mesh.C, style);
}

void Rasterizer::draw_mesh(const Points& V, const Triangles& F, const Points& N, const Colors& C,
                           const SurfaceStyle& style) {
  const Eigen::Index nv = V.rows();
  if (N.rows() != 0 && N.rows() != nv)
    throw InvalidInput("draw_mesh: " + std::to_string(N.rows()) + " normals for " + std::to_string(nv) + " vertices");
  if (C.rows() != 0 && C.rows() != nv)
    throw InvalidInput("draw_mesh: " + std::to_string(C.rows()) + " colours for " + std::to_string(nv) + " vertices");
  if (F.rows() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= nv))
    throw InvalidInput("draw_mesh: a triangle index is outside [0, " + std::to_string(nv) + ")");
  if (nv == 0) return;
  const bool first_surface = !surface_drawn_;
  surface_drawn_ = true;

  const Lighting light = make_lighting(camera_);
  const bool perspective = camera_.projection == Projection::Perspective;
  const Vec3 f = camera_.forward();
  const Vec3 uniform = to_vec(style.colour);
  auto base_colour = [&](Index i) -> Vec3 {
    return C.rows() ? Vec3(C(i, 0), C(i, 1), C(i, 2)) : uniform;
  };

  const std::vector<Projected> P = camera_.project_all(V, w_, h_);

  if (F.rows() == 0) {  // point cloud: shaded splats that write depth
    const double r = std::max(0.5, style.point_radius_px * options_.supersample);
    for (Eigen::Index i = 0; i < nv; ++i) {
      const Projected& p = P[i];
      if (perspective && p.depth <= camera_.near) continue;
      Vec3 n = N.rows() ? Vec3(N.row(i).transpose()) : Vec3(-f);
      bool front = true;
      if (n.squaredNorm() == 0) n = -f;
      n.normalize();
      if (n.dot(light.headlight) < 0) {
        n = -n;
        front = false;
      }
      const Rgb c = scale_rgb(shade(base_colour(static_cast<Index>(i)), n, front, light, style));
      const Span xs = pixel_span(p.x - r, p.x + r, w_), ys = pixel_span(p.y - r, p.y + r, h_);
      if (!std::isfinite(p.depth)) continue;
      for (int y = ys.lo; y <= ys.hi; ++y)
        for (int x = xs.lo; x <= xs.hi; ++x) {
          const double dx = x + 0.5 - p.x, dy = y + 0.5 - p.y;
          if (dx * dx + dy * dy > r * r) continue;
          const size_t idx = static_cast<size_t>(y) * w_ + x;
          if (p.depth < depth_[idx]) {
            depth_[idx] = static_cast<float>(p.depth);
            colour_.set(x, y, c);
          }
        }
    }
    return;
  }

  const Points normals = (style.smooth && N.rows() == 0) ? mesh::vertex_normals(V, F) : Points();
  const Points& vn = N.rows() ? N : normals;

  // Deferred shading: pass 1 finds, per pixel, the nearest triangle of this call (depth test as
  // in a direct renderer: of equal depths the first drawn wins); pass 2 shades each covered pixel
  // once with that triangle, without shading surfaces that are drawn over later (the back of the
  // torso).
  // Per triangle: its signed area in the image, twice (negative: it faces the camera), and
  // whether it faces the camera, in an array of its own (one byte a triangle: pass 2 looks it
  // up for every sample's winner, and 16-byte records made that lookup a cache miss).
  std::vector<double> tri_area(static_cast<size_t>(F.rows()), 0.0);
  std::vector<std::uint8_t> tri_front(static_cast<size_t>(F.rows()), 0);
  // Triangles in screen tiles of 32 × 32 pixels (row-major; stable within a tile), so that the
  // depth and winner buffers are walked with locality whatever the mesh's triangle order; the
  // triangles facing the camera first, then the back faces (the inside of the far wall of the
  // torso, mostly hidden behind the near one), of which those that lie behind everything drawn
  // in their screen area are skipped without visiting their pixels (a coarse depth test).
  constexpr int kTile = 32;
  const int tiles_x = (w_ + kTile - 1) / kTile, tiles_y = (h_ + kTile - 1) / kTile;
  const int tiles = tiles_x * tiles_y;
  std::vector<std::int32_t> bucket_of(static_cast<size_t>(F.rows()), -1);  // -1: nothing to draw
  std::vector<std::int32_t> bucket_start(2 * static_cast<size_t>(tiles) + 1, 0);
  bool all_fixed = true;  // every drawn corner in the fixed-point range
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const Index i0 = F(t, 0), i1 = F(t, 1), i2 = F(t, 2);
    const Projected &p0 = P[i0], &p1 = P[i1], &p2 = P[i2];
    if (perspective && (p0.depth <= camera_.near || p1.depth <= camera_.near || p2.depth <= camera_.near))
      continue;
    if (!(std::isfinite(p0.depth) && std::isfinite(p1.depth) && std::isfinite(p2.depth))) continue;
    // The image is y-down, so a triangle whose corners run counter-clockwise seen from the
    // camera (its normal towards the camera) has a negative signed area in the image.
    const double area = edge(p0, p1, p2.x, p2.y);
    if (!(std::abs(area) > 1e-12)) continue;
    const bool front = area < 0;
    tri_area[static_cast<size_t>(t)] = area;
    tri_front[static_cast<size_t>(t)] = front;
    all_fixed = all_fixed && fixed_range(p0) && fixed_range(p1) && fixed_range(p2);
    const double cx = (p0.x + p1.x + p2.x) / 3.0, cy = (p0.y + p1.y + p2.y) / 3.0;
    const int tx = std::clamp(pixel_index(cx), 0, w_ - 1) / kTile, ty = std::clamp(pixel_index(cy), 0, h_ - 1) / kTile;
    const int bucket = (front ? 0 : tiles) + ty * tiles_x + tx;
    bucket_of[static_cast<size_t>(t)] = bucket;
    ++bucket_start[static_cast<size_t>(bucket) + 1];
  }
  for (size_t k = 1; k < bucket_start.size(); ++k) bucket_start[k] += bucket_start[k - 1];
  const size_t n_front = static_cast<size_t>(bucket_start[static_cast<size_t>(tiles)]);
  std::vector<std::int32_t> order(static_cast<size_t>(bucket_start.back()));
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    if (bucket_of[static_cast<size_t>(t)] >= 0)
      order[static_cast<size_t>(bucket_start[static_cast<size_t>(bucket_of[t])]++)] = static_cast<std::int32_t>(t);
  bucket_of = {};
  // The triangles' projected corners gathered in that order by a loop of their own (its loads
  // are independent, so their cache misses overlap) for the loop below to read one after the
  // other instead of chasing F and P from inside its longer body; kGather triangles at a time,
  // into a buffer that stays in the cache (not 72 bytes a triangle for the whole mesh: 17 MB
  // for the report's scan, written and read back through memory and faulted in by each figure).
  constexpr size_t kGather = 2048;
  std::vector<std::array<Projected, 3>> corners(std::min(order.size(), kGather));
  auto gather = [&](size_t first) {
    const size_t end = std::min(order.size(), first + kGather);
    for (size_t k = first; k < end; ++k) {
      const std::int32_t t = order[k];
      corners[k - first] = {P[F(t, 0)], P[F(t, 1)], P[F(t, 2)]};
    }
  };

  // The coarse depth test of the back faces (BlockFar), filled after the front faces.
  BlockFar block_far(w_, h_);

  const int ss = options_.supersample;
  // The first surface drawn (the buffers hold nothing yet), orthographic, in the fixed-point range.
  const bool adaptive = options_.adaptive_supersample && ss > 1 && !perspective && first_surface && all_fixed;

  // Depths of one output pixel's samples within kFlatPixels output pixels of each other: the
  // surface does not jump (no silhouette or fold) inside it.
  constexpr double kFlatPixels = 2.0;
  const double flat_depth_ortho = kFlatPixels * camera_.world_per_pixel(0.0, options_.height);  // orthographic: any depth

  // The surface at the image point (px, py) (a sample's centre is (x + 0.5, y + 0.5)) on
  // triangle t: its unit normal (facing the viewer) and base colour.
  struct Sample {
    Vec3 n, base;
  };
  auto sample_at = [&](double px, double py, std::int32_t t) -> Sample {
    const bool front = tri_front[static_cast<size_t>(t)] != 0;
    const Index i0 = F(t, 0), i1 = F(t, 1), i2 = F(t, 2);
    const Projected &p0 = P[i0], &p1 = P[i1], &p2 = P[i2];
    const double inv_area = 1.0 / tri_area[static_cast<size_t>(t)];
    double b0 = edge(p1, p2, px, py) * inv_area;
    double b1 = edge(p2, p0, px, py) * inv_area;
    double b2 = edge(p0, p1, px, py) * inv_area;
    if (perspective) {  // perspective-correct barycentrics (orthographic: they sum to 1 already)
      b0 /= p0.depth;
      b1 /= p1.depth;
      b2 /= p2.depth;
      const double sum = b0 + b1 + b2;
      b0 /= sum;
      b1 /= sum;
      b2 /= sum;
    }
    Vec3 n = Vec3::Zero();
    if (style.smooth) n = b0 * Vec3(vn.row(i0)) + b1 * Vec3(vn.row(i1)) + b2 * Vec3(vn.row(i2));
    if (!(n.squaredNorm() > 0)) {  // flat shading, or no usable vertex normals: the face's normal
      const Vec3 v0 = V.row(i0);
      n = (Vec3(V.row(i1)) - v0).cross(Vec3(V.row(i2)) - v0);
      if (!(n.squaredNorm() > 0)) n = front ? Vec3(-f) : Vec3(f);  // degenerate in 3D
    }
    n.normalize();
    if (!front) n = -n;
    // Interpolated normals may turn away at silhouettes; keep them facing the viewer.
    const Vec3 view = perspective ? Vec3((camera_.eye - (b0 * Vec3(V.row(i0)) + b1 * Vec3(V.row(i1)) +
                                                           b2 * Vec3(V.row(i2))))
                                             .normalized())
                                  : Vec3(-f);
    if (n.dot(view) < 0) n = (n - 1.0 * n.dot(view) * view).normalized();
    return {n, b0 * base_colour(i0) + b1 * base_colour(i1) + b2 * base_colour(i2)};
  };
  auto shade_sample = [&](int x, int y, std::int32_t t) {
    const Sample s = sample_at(x + 0.5, y + 0.5, t);
    return scale_rgb(shade(s.base, s.n, tri_front[static_cast<size_t>(t)] != 0, light, style));
  };

  if (adaptive) {
    // Supersampling only where a pixel needs it (RasterOptions::adaptive_supersample): pass 1 at
    // one sample per output pixel (its centre); the pixels next to a change of coverage, of facing
    // or a jump of depth (silhouettes, folds, the scan's holes and borders: 8-neighbourhood) are
    // marked and pass 1 runs again over their ss × ss samples only; pass 2 lights an unmarked
    // pixel once, at its centre, and shades a marked one sample by sample (once when a single
    // triangle covers all of it). The supersampled buffers are filled as the full path fills
    // them (an unmarked pixel's colour and depth in all its samples), so the overlays and
    // resolve() see no difference.
    const int W = options_.width, H = options_.height;
    const size_t n_pixels = static_cast<size_t>(W) * H;
    std::vector<float> depth_lo(n_pixels, kEmpty);
    std::vector<std::int32_t> winner_lo(n_pixels, -1);
    int lx0 = W, ly0 = H, lx1 = -1, ly1 = -1;  // a box around the pixels won
    // Per bucket, a box (in samples) around its triangles: the refinement skips the buckets that
    // reach no marked pixel.
    struct Box {
      int x0, y0, x1, y1;
    };
    const size_t n_buckets = 2 * static_cast<size_t>(tiles);
    std::vector<Box> bucket_box(n_buckets, Box{w_, h_, -1, -1});
    // The coarse depth test of the back faces, by blocks of output pixels.
    BlockFar far_lo(W, H);
    const std::int64_t step_lo = static_cast<std::int64_t>(ss) << kSubpixelBits;
    const std::int64_t half_lo = static_cast<std::int64_t>(ss) << (kSubpixelBits - 1);
    // Per triangle (in drawing order), its box of samples for the refinement, which then reads
    // the corners of only the triangles that reach a marked pixel (x0 > x1: no sample).
    std::vector<std::array<std::uint16_t, 4>> tri_box(order.size(), {1, 0, 0, 0});
    size_t k = 0;
    for (size_t b = 0; b < n_buckets; ++b) {
      if (b == static_cast<size_t>(tiles)) far_lo.fill([&](size_t p) { return depth_lo[p]; });
      for (const size_t end = static_cast<size_t>(bucket_start[b]); k < end; ++k) {
        if (k % kGather == 0) gather(k);
        const std::int32_t t = order[k];
        const std::array<Projected, 3>& c = corners[k % kGather];
        const Projected &p0 = c[0], &p1 = c[1], &p2 = c[2];
        const double min_x = std::min({p0.x, p1.x, p2.x}), max_x = std::max({p0.x, p1.x, p2.x});
        const double min_y = std::min({p0.y, p1.y, p2.y}), max_y = std::max({p0.y, p1.y, p2.y});
        const Span hx = pixel_span(min_x, max_x, w_), hy = pixel_span(min_y, max_y, h_);
        if (hx.lo <= hx.hi && hy.lo <= hy.hi) {  // (a triangle can hold a pixel's centre and no sample's)
          Box& box = bucket_box[b];
          box = {std::min(box.x0, hx.lo), std::min(box.y0, hy.lo), std::max(box.x1, hx.hi), std::max(box.y1, hy.hi)};
          tri_box[k] = {static_cast<std::uint16_t>(hx.lo), static_cast<std::uint16_t>(hy.lo),
                        static_cast<std::uint16_t>(hx.hi), static_cast<std::uint16_t>(hy.hi)};
        }
        const Span xs = pixel_span(min_x / ss, max_x / ss, W), ys = pixel_span(min_y / ss, max_y / ss, H);
        if (xs.lo > xs.hi || ys.lo > ys.hi) continue;
        if (k >= n_front && far_lo.hidden(xs.lo, ys.lo, xs.hi, ys.hi, std::min({p0.depth, p1.depth, p2.depth}))) continue;
        const auto g = fixed_edges(p0, p1, p2, xs.lo * step_lo + half_lo, ys.lo * step_lo + half_lo, step_lo);
        if (!g) continue;
        const Linear ez = triangle_planes(p0, p1, p2, tri_area[static_cast<size_t>(t)]).depth;
        if (fill_box(g->g0, g->g1, g->g2, xs, ys, ez, ss, depth_lo.data(), winner_lo.data(), W, t)) {
          lx0 = std::min(lx0, xs.lo);
          lx1 = std::max(lx1, xs.hi);
          ly0 = std::min(ly0, ys.lo);
          ly1 = std::max(ly1, ys.hi);
        }
      }
    }
    if (lx1 < 0) return;  // nothing drawn
    // The pixels to refine: both pixels of each 8-neighbour pair that differ in coverage, in
    // facing, or in depth by more than kEdgeDepthPixels output pixels: an occluding edge, not the
    // scan's noise or a steep slope (with 2 pixels, a third of a side figure's surface was
    // marked, mostly noise; the silhouette of a steep slope is marked by its coverage).
    constexpr double kEdgeDepthPixels = 8.0;
    const double edge_depth = kEdgeDepthPixels * camera_.world_per_pixel(0.0, options_.height);
    const int mx0 = std::max(0, lx0 - 1), mx1 = std::min(W - 1, lx1 + 1);
    const int my0 = std::max(0, ly0 - 1), my1 = std::min(H - 1, ly1 + 1);
    std::vector<std::uint8_t> mark(n_pixels, 0);
    auto differ = [&](size_t p, size_t q) {
      const std::int32_t a = winner_lo[p], b = winner_lo[q];
      if ((a < 0) != (b < 0)) return true;
      if (a < 0) return false;
      return tri_front[static_cast<size_t>(a)] != tri_front[static_cast<size_t>(b)] ||
             std::abs(depth_lo[p] - depth_lo[q]) > edge_depth;
    };
    auto pair = [&](size_t p, size_t q) {
      if (differ(p, q)) mark[p] = mark[q] = 1;
    };
    for (int y = my0; y <= my1; ++y)
      for (int x = mx0; x <= mx1; ++x) {
        const size_t p = static_cast<size_t>(y) * W + x;
        if (x < mx1) pair(p, p + 1);
        if (y == my1) continue;
        pair(p, p + W);
        if (x < mx1) pair(p, p + W + 1);
        if (x > mx0) pair(p, p + W - 1);
      }
    // Marked pixels numbered in raster order (their samples' slots) and counted in a summed-area
    // table (how many in a box: four lookups).
    std::vector<std::int32_t> slot_of(n_pixels, -1);
    std::vector<std::int32_t> sat(static_cast<size_t>(W + 1) * (H + 1), 0);
    std::int32_t n_marked = 0;
    for (int y = 0; y < H; ++y) {
      std::int32_t row = 0;
      for (int x = 0; x < W; ++x) {
        const size_t p = static_cast<size_t>(y) * W + x;
        if (mark[p]) slot_of[p] = n_marked++;
        row += mark[p];
        sat[static_cast<size_t>(y + 1) * (W + 1) + x + 1] = sat[static_cast<size_t>(y) * (W + 1) + x + 1] + row;
      }
    }
    mark = {};
    auto marked_in = [&](int x0, int y0, int x1, int y1) {  // output pixels, inclusive
      const size_t r0 = static_cast<size_t>(y0) * (W + 1), r1 = static_cast<size_t>(y1 + 1) * (W + 1);
      return sat[r1 + x1 + 1] - sat[r1 + x0] - sat[r0 + x1 + 1] + sat[r0 + x0] > 0;
    };
    const int s2 = ss * ss;
    std::vector<float> depth_s(static_cast<size_t>(n_marked) * s2, kEmpty);
    std::vector<std::int32_t> winner_s(static_cast<size_t>(n_marked) * s2, -1);
    k = 0;
    for (size_t b = 0; b < n_buckets; ++b) {
      const size_t begin = k, end = static_cast<size_t>(bucket_start[b]);
      k = end;
      if (n_marked == 0) break;
      if (b == static_cast<size_t>(tiles))  // a marked pixel's farthest sample, an unmarked pixel's depth
        far_lo.fill([&](size_t p) {
          const std::int32_t s = slot_of[p];
          if (s < 0) return depth_lo[p];
          float far = 0.0f;
          for (int j = 0; j < s2; ++j) far = std::max(far, depth_s[static_cast<size_t>(s) * s2 + j]);
          return far;
        });
      const Box& box = bucket_box[b];
      if (begin == end || box.x1 < 0 || !marked_in(box.x0 / ss, box.y0 / ss, box.x1 / ss, box.y1 / ss)) continue;
      for (size_t kk = begin; kk < end; ++kk) {
        const std::array<std::uint16_t, 4>& tb = tri_box[kk];
        if (tb[0] > tb[2]) continue;
        const int qx0 = tb[0] / ss, qy0 = tb[1] / ss, qx1 = tb[2] / ss, qy1 = tb[3] / ss;
        if (!marked_in(qx0, qy0, qx1, qy1)) continue;
        const std::int32_t t = order[kk];
        const Projected &p0 = P[F(t, 0)], &p1 = P[F(t, 1)], &p2 = P[F(t, 2)];
        if (kk >= n_front && far_lo.hidden(qx0, qy0, qx1, qy1, std::min({p0.depth, p1.depth, p2.depth}))) continue;
        const int sx0 = qx0 * ss, sy0 = qy0 * ss;  // the samples' origin
        const auto g = fixed_edges(p0, p1, p2, sample_centre(sx0), sample_centre(sy0), std::int64_t{1} << kSubpixelBits);
        if (!g) continue;
        const FixedEdge &g0 = g->g0, &g1 = g->g1, &g2 = g->g2;
        const Linear ez = triangle_planes(p0, p1, p2, tri_area[static_cast<size_t>(t)]).depth;
        for (int ly = qy0; ly <= qy1; ++ly)
          for (int lx = qx0; lx <= qx1; ++lx) {
            const std::int32_t s = slot_of[static_cast<size_t>(ly) * W + lx];
            if (s < 0) continue;
            for (int dy = 0; dy < ss; ++dy) {
              const int y = ly * ss + dy;
              const std::int64_t oy = y - sy0;
              for (int dx = 0; dx < ss; ++dx) {
                const int x = lx * ss + dx;
                const std::int64_t ox = x - sx0;
                const std::int64_t a0 = g0.at_origin + ox * g0.step_x + oy * g0.step_y;
                const std::int64_t a1 = g1.at_origin + ox * g1.step_x + oy * g1.step_y;
                const std::int64_t a2 = g2.at_origin + ox * g2.step_x + oy * g2.step_y;
                if ((a0 | a1 | a2) < 0) continue;
                const double depth = ez.at(x + 0.5, y + 0.5);
                const size_t j = static_cast<size_t>(s) * s2 + dy * ss + dx;
                if (!(depth < depth_s[j])) continue;
                depth_s[j] = static_cast<float>(depth);
                winner_s[j] = t;
              }
            }
          }
      }
    }
    // Pass 2: the samples' colours and depths.
    for (int ly = my0; ly <= my1; ++ly)
      for (int lx = mx0; lx <= mx1; ++lx) {
        const size_t p = static_cast<size_t>(ly) * W + lx;
        const std::int32_t s = slot_of[p];
        const int x0 = lx * ss, y0 = ly * ss;
        if (s < 0) {
          const std::int32_t t = winner_lo[p];
          if (t < 0) continue;
          const Sample m = sample_at(x0 + 0.5 * ss, y0 + 0.5 * ss, t);
          const Rgb c = scale_rgb(shade(m.base, m.n, tri_front[static_cast<size_t>(t)] != 0, light, style));
          for (int dy = 0; dy < ss; ++dy)
            for (int dx = 0; dx < ss; ++dx) {
              colour_.set(x0 + dx, y0 + dy, c);
              depth_[static_cast<size_t>(y0 + dy) * w_ + x0 + dx] = depth_lo[p];
            }
          continue;
        }
        const std::int32_t* ws = &winner_s[static_cast<size_t>(s) * s2];
        const float* ds = &depth_s[static_cast<size_t>(s) * s2];
        bool one = ws[0] >= 0;
        for (int j = 1; j < s2 && one; ++j) one = ws[j] == ws[0];
        Rgb one_colour{};
        if (one) {
          const Sample m = sample_at(x0 + 0.5 * ss, y0 + 0.5 * ss, ws[0]);
          one_colour = scale_rgb(shade(m.base, m.n, tri_front[static_cast<size_t>(ws[0])] != 0, light, style));
        }
        for (int dy = 0; dy < ss; ++dy)
          for (int dx = 0; dx < ss; ++dx) {
            const int j = dy * ss + dx;
            if (ws[j] < 0) continue;
            colour_.set(x0 + dx, y0 + dy, one ? one_colour : shade_sample(x0 + dx, y0 + dy, ws[j]));
            depth_[static_cast<size_t>(y0 + dy) * w_ + x0 + dx] = ds[j];
          }
      }
    return;
  }

  std::vector<std::int32_t> winner(static_cast<size_t>(w_) * h_, -1);
  int bx0 = w_, by0 = h_, bx1 = -1, by1 = -1;  // a box around the pixels won by this call
  for (size_t k = 0; k < order.size(); ++k) {
    if (k == n_front) block_far.fill([&](size_t p) { return depth_[p]; });
    if (k % kGather == 0) gather(k);
    const std::int32_t t = order[k];
    const std::array<Projected, 3>& c = corners[k % kGather];
    const Projected &p0 = c[0], &p1 = c[1], &p2 = c[2];
    const double area = tri_area[static_cast<size_t>(t)];
    const Span xs = pixel_span(std::min({p0.x, p1.x, p2.x}), std::max({p0.x, p1.x, p2.x}), w_);
    const Span ys = pixel_span(std::min({p0.y, p1.y, p2.y}), std::max({p0.y, p1.y, p2.y}), h_);
    if (xs.lo > xs.hi || ys.lo > ys.hi) continue;
    // Every depth inside the triangle (perspective-correct too) lies between its corners'.
    if (k >= n_front && block_far.hidden(xs.lo, ys.lo, xs.hi, ys.hi, std::min({p0.depth, p1.depth, p2.depth}))) continue;

    if (!perspective && fixed_range(p0) && fixed_range(p1) && fixed_range(p2)) {
      // Orthographic: exact integer edge functions over the triangle's box, the depth linear in
      // the sample position (one multiply-add per sample instead of a perspective division).
      const auto g = fixed_edges(p0, p1, p2, sample_centre(xs.lo), sample_centre(ys.lo), std::int64_t{1} << kSubpixelBits);
      if (!g) continue;  // thinner than a 256th of a sample
      const Linear ez = triangle_planes(p0, p1, p2, area).depth;
      if (fill_box(g->g0, g->g1, g->g2, xs, ys, ez, 1, depth_.data(), winner.data(), w_, t)) {
        bx0 = std::min(bx0, xs.lo);
        bx1 = std::max(bx1, xs.hi);
        by0 = std::min(by0, ys.lo);
        by1 = std::max(by1, ys.hi);
      }
      continue;
    }

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
        const size_t idx = static_cast<size_t>(y) * w_ + x;
        if (!(depth < depth_[idx])) continue;
        depth_[idx] = static_cast<float>(depth);
        winner[idx] = static_cast<std::int32_t>(t);
        wrote = true;
      }
    }
    if (wrote) {  // pass 2 visits this box (conservative: it skips the pixels nobody won)
      bx0 = std::min(bx0, xs.lo);
      bx1 = std::max(bx1, xs.hi);
      by0 = std::min(by0, ys.lo);
      by1 = std::max(by1, ys.hi);
    }
  }

  // Pass 2, by output pixel (a block of ss × ss samples). A block whose samples all show this
  // call's surface, facing the same way and within kFlatPixels output pixels of depth of each
  // other (not across a silhouette), is lit once with its samples' mean normal and colour, which
  // for the small variations inside one pixel is their mean shade to within a grey level (when
  // one triangle covers the whole block: its normal and colour at the block's centre, their mean
  // up to the normalisation); other blocks are shaded sample by sample (edges stay anti-aliased).
  for (int y0 = by0 / ss * ss; y0 <= by1; y0 += ss)
    for (int x0 = bx0 / ss * ss; x0 <= bx1; x0 += ss) {
      const std::int32_t t0 = winner[static_cast<size_t>(y0) * w_ + x0];
      bool flat = t0 >= 0 && ss > 1, one_triangle = true;
      if (flat) {
        const std::uint8_t front = tri_front[static_cast<size_t>(t0)];
        float lo = depth_[static_cast<size_t>(y0) * w_ + x0], hi = lo;
        for (int dy = 0; dy < ss && flat; ++dy)
          for (int dx = 0; dx < ss && flat; ++dx) {
            const size_t idx = static_cast<size_t>(y0 + dy) * w_ + x0 + dx;
            flat = winner[idx] >= 0 && tri_front[static_cast<size_t>(winner[idx])] == front;
            one_triangle = one_triangle && winner[idx] == t0;
            lo = std::min(lo, depth_[idx]);
            hi = std::max(hi, depth_[idx]);
          }
        flat = flat && hi - lo <= (perspective ? kFlatPixels * camera_.world_per_pixel(lo, options_.height) : flat_depth_ortho);
      }
      if (flat) {
        Sample mean{Vec3::Zero(), Vec3::Zero()};
        if (one_triangle) {
          mean = sample_at(x0 + 0.5 * ss, y0 + 0.5 * ss, t0);
          mean.base *= ss * ss;
        } else {
          // The block's triangles (the small triangles of a dense scan: two or three a block),
          // each sampled once at the mean of its samples' positions and weighted by their
          // number: the interpolated normal and colour are linear in the position, so this is
          // their mean but for the normalisation of the normal, well below a grey level within
          // one pixel.
          std::array<std::int32_t, 16> tris;
          std::array<int, 16> count{};
          std::array<double, 16> sum_x{}, sum_y{};
          int distinct = 0;
          for (int dy = 0; dy < ss; ++dy)
            for (int dx = 0; dx < ss; ++dx) {
              const std::int32_t t = winner[static_cast<size_t>(y0 + dy) * w_ + x0 + dx];
              int j = 0;
              while (j < distinct && tris[j] != t) ++j;
              if (j == distinct) tris[distinct++] = t;
              ++count[j];
              sum_x[j] += x0 + dx + 0.5;
              sum_y[j] += y0 + dy + 0.5;
            }
          for (int j = 0; j < distinct; ++j) {
            const Sample s = sample_at(sum_x[j] / count[j], sum_y[j] / count[j], tris[j]);
            mean.n += count[j] * s.n;
            mean.base += count[j] * s.base;
          }
        }
        const double norm = mean.n.norm();
        const Rgb c = norm > 0 ? scale_rgb(shade(mean.base / (ss * ss), mean.n / norm, tri_front[static_cast<size_t>(t0)] != 0,
                                                 light, style))
                               : shade_sample(x0, y0, t0);
        for (int dy = 0; dy < ss; ++dy)
          for (int dx = 0; dx < ss; ++dx) colour_.set(x0 + dx, y0 + dy, c);
        continue;
      }
      for (int y = y0; y < y0 + ss; ++y)
        for (int x = x0; x < x0 + ss; ++x) {
          const std::int32_t t = winner[static_cast<size_t>(y) * w_ + x];
          if (t >= 0) colour_.set(x, y, shade_sample(x, y, t));
        }
    }
}

bool Rasterizer::overlay_visible_at(int x, int y, double depth) const {
  const float surface = depth_[static_cast<size_t>(y) * w_ + x];
  return !(depth - options_.depth_bias > surface);
}

void Rasterizer::paint_overlay(int x, int y, Rgb colour, bool visible, double alpha, bool allow_hidden) {
  if (ink_.empty()) ink_.assign(static_cast<size_t>(w_) * h_, 0);  // on the first overlay pixel only
  const size_t idx = static_cast<size_t>(y) * w_ + x;
  if (visible) {
    if (alpha >= 1.0) {
      colour_.set(x, y, colour);
      ink_[idx] = kVisibleInk;
    } else if (ink_[idx] != call_id_) {
      colour_.set(x, y, mix(colour_.at(x, y), colour, alpha));
      ink_[idx] = call_id_;
    }
    return;
  }
  if (!allow_hidden || !options_.show_hidden_overlays) return;
  if (ink_[idx] == kVisibleInk || ink_[idx] == call_id_) return;
  colour_.set(x, y, mix(colour_.at(x, y), colour, alpha * options_.hidden_alpha));
  ink_[idx] = call_id_;
}

void Rasterizer::draw_segment(const Projected& a, const Projected& b, double radius, Rgb colour,
                              double alpha, bool allow_hidden) {
  const bool perspective = camera_.projection == Projection::Perspective;
  if (perspective && (a.depth <= camera_.near || b.depth <= camera_.near)) return;
  if (!(std::isfinite(a.depth) && std::isfinite(b.depth))) return;
  const Span xs = pixel_span(std::min(a.x, b.x) - radius, std::max(a.x, b.x) + radius, w_);
  const Span ys = pixel_span(std::min(a.y, b.y) - radius, std::max(a.y, b.y) + radius, h_);
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  for (int y = ys.lo; y <= ys.hi; ++y)
    for (int x = xs.lo; x <= xs.hi; ++x) {
      const double px = x + 0.5 - a.x, py = y + 0.5 - a.y;
      const double t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
      const double ex = px - t * dx, ey = py - t * dy;
      if (ex * ex + ey * ey > radius * radius) continue;
      const double depth =
          perspective ? 1.0 / ((1.0 - t) / a.depth + t / b.depth) : (1.0 - t) * a.depth + t * b.depth;
      paint_overlay(x, y, colour, overlay_visible_at(x, y, depth), alpha, allow_hidden);
    }
}

void Rasterizer::draw_polyline(const Points& P, bool closed, const LineStyle& style) {
  if (!(style.width_px > 0)) throw InvalidInput("draw_polyline: width_px must be > 0");
  if (P.rows() == 0) return;
  next_call();
  const double radius = 0.5 * style.width_px * options_.supersample;
  const std::vector<Projected> q = camera_.project_all(P, w_, h_);
  if (q.size() == 1) {
    draw_segment(q[0], q[0], radius, style.colour, 1.0, true);
    return;
  }
  for (size_t i = 0; i + 1 < q.size(); ++i) draw_segment(q[i], q[i + 1], radius, style.colour, 1.0, true);
  if (closed && q.size() > 2) draw_segment(q.back(), q.front(), radius, style.colour, 1.0, true);
}

void Rasterizer::draw_point(const Vec3& p, const PointStyle& style) {
  if (!(style.radius > 0)) throw InvalidInput("draw_point: radius must be > 0");
  const Projected c = project_internal(p);
  if (camera_.projection == Projection::Perspective && c.depth <= camera_.near) return;
  next_call();
  const int ss = options_.supersample;
  const double r_out = style.unit == SizeUnit::Pixels
                           ? style.radius
                           : style.radius / camera_.world_per_pixel(c.depth, options_.height);
  const double r = std::max(0.75, r_out * ss);
  if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.depth))) return;
  const int cx = pixel_index(c.x), cy = pixel_index(c.y);
  const bool inside = cx >= 0 && cy >= 0 && cx < w_ && cy < h_;
  const bool visible = !inside || overlay_visible_at(cx, cy, c.depth);
  const double rim = std::max(1.0, 0.2 * r);
  const Vec3 base = to_vec(style.colour);
  const Rgb rim_colour = mix(style.colour, {0, 0, 0}, 0.6);
  const Span xs = pixel_span(c.x - r, c.x + r, w_), ys = pixel_span(c.y - r, c.y + r, h_);
  for (int y = ys.lo; y <= ys.hi; ++y)
    for (int x = xs.lo; x <= xs.hi; ++x) {
      const double dx = x + 0.5 - c.x, dy = y + 0.5 - c.y;
      const double d = std::sqrt(dx * dx + dy * dy);
      if (d > r) continue;
      Rgb colour = rim_colour;
      if (d <= r - rim) {
        // Shade the disc as a sphere lit from the upper left.
        const double ri = r - rim;
        const double nx = dx / ri, ny = dy / ri;
        const double nz = std::sqrt(std::max(0.0, 1.0 - nx * nx - ny * ny));
        const double lambert = std::max(0.0, (-0.4 * nx - 0.4 * ny + 0.82 * nz));
        const double highlight = std::pow(lambert, 12.0) * 0.45;
        colour = scale_rgb(base * (0.55 + 0.45 * lambert) + Vec3::Constant(255.0 * highlight));
      }
      paint_overlay(x, y, colour, visible, 1.0, true);
    }
}

void Rasterizer::draw_wireframe(const Points& V, const Triangles& F, const WireframeStyle& style) {
  if (!(style.alpha > 0 && style.alpha <= 1)) throw InvalidInput("draw_wireframe: alpha must be in (0, 1]");
  if (!(style.width_px > 0)) throw InvalidInput("draw_wireframe: width_px must be > 0");
  if (F.rows() == 0) return;
  if (F.minCoeff() < 0 || F.maxCoeff() >= V.rows())
    throw InvalidInput("draw_wireframe: a triangle index is outside the vertex range");
  next_call();
  const auto edges = mesh::unique_edges(F, static_cast<Index>(V.rows()));
  const std::vector<Projected> q = camera_.project_all(V, w_, h_);
  const double radius = 0.5 * style.width_px * options_.supersample;
  for (const auto& [a, b] : edges) draw_segment(q[a], q[b], radius, style.colour, style.alpha, false);
}

bool Rasterizer::is_visible(const Vec3& p) const {
  const Projected c = project_internal(p);
  if (camera_.projection == Projection::Perspective && c.depth <= camera_.near) return false;
  const int x = pixel_index(c.x), y = pixel_index(c.y);
  if (x < 0 || y < 0 || x >= w_ || y >= h_) return false;
  return overlay_visible_at(x, y, c.depth);
}

double Rasterizer::surface_coverage() const {
  size_t covered = 0;
  for (float d : depth_) covered += d < kEmpty ? 1 : 0;
  return static_cast<double>(covered) / static_cast<double>(depth_.size());
}

Image Rasterizer::resolve() const { return colour_.downsampled(options_.supersample); }

}  // namespace breastfit::render
