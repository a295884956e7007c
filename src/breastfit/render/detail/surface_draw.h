#pragma once
/// \file One draw_mesh call's triangles prepared once for the rasterizer's surface passes (private
/// to the render layer): the corners projected to samples, the triangles' facing and drawing order
/// (by screen tile, front faces first), and the surface's normal and colour at any image point of
/// a triangle; with the buffers the passes draw into.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/render/camera.h"
#include "breastfit/render/detail/raster_setup.h"
#include "breastfit/render/detail/shading.h"
#include "breastfit/render/image.h"
#include "breastfit/render/rasterizer.h"

namespace breastfit::render::detail {

/// The rasterizer's supersampled colour and depth buffers, which a surface is drawn into.
struct SurfaceTarget {
  Image& colour;              ///< w × h samples
  std::vector<float>& depth;  ///< w × h samples, kEmpty where nothing is drawn
  int w, h;                   ///< size in samples
  int width, height;          ///< size in output pixels
  int ss;                     ///< samples per output pixel, each way
};

/// A surface point of a triangle: its unit normal (facing the viewer) and base colour.
struct Sample {
  Vec3 n, base;
};

/// A mesh's triangles as one draw_mesh call draws them into a w × h sample grid. Deferred shading:
/// pass 1 finds, per sample, the nearest triangle of this call (depth test as in a direct
/// renderer: of equal depths the first drawn wins); pass 2 shades each covered sample (or pixel)
/// once with that triangle, without shading surfaces that are drawn over later (the back of the
/// torso). The camera, V, F, C and style are kept by reference.
struct SurfaceDraw {
  SurfaceDraw(const Camera& camera, const Points& V, const Triangles& F, const Points& N, const Colors& C,
              const SurfaceStyle& style, int w, int h);
  SurfaceDraw(const SurfaceDraw&) = delete;
  SurfaceDraw& operator=(const SurfaceDraw&) = delete;

  const Camera& camera;
  const Points& V;
  const Triangles& F;
  const Colors& C;
  const SurfaceStyle& style;
  const bool perspective;
  const Vec3 forward;  ///< the camera's viewing direction
  const Lighting light;
  const Vec3 uniform_colour;  ///< the base colour without vertex colours
  const std::vector<Projected> P;  ///< the vertices in sample coordinates

 private:
  const Points computed_normals_;  // area-weighted vertex normals when smooth and N is empty

 public:
  const Points& vn;  ///< the vertex normals interpolated when smooth (N, else computed_normals_)

  /// Per triangle: its signed area in the image, twice (negative: it faces the camera; 0: not
  /// drawn), and whether it faces the camera, in an array of its own (one byte a triangle: pass 2
  /// looks it up for every sample's winner, and 16-byte records made that lookup a cache miss).
  std::vector<double> area;
  std::vector<std::uint8_t> front;
  /// The drawn triangles in screen tiles of kTile × kTile samples (row-major; stable within a
  /// tile), so that the depth and winner buffers are walked with locality whatever the mesh's
  /// triangle order: the `tiles` buckets of the triangles facing the camera, then the `tiles`
  /// buckets of the back faces (the inside of the far wall of the torso, mostly hidden behind the
  /// near one, of which those that lie behind everything drawn in their screen area are skipped
  /// by a coarse depth test, BlockFar). Bucket b is order[bucket_end[b − 1], bucket_end[b]).
  static constexpr int kTile = 32;
  int tiles = 0;
  std::vector<std::int32_t> bucket_end;
  std::vector<std::int32_t> order;
  size_t n_front = 0;     ///< order[0, n_front) face the camera
  bool all_fixed = true;  ///< every drawn corner in the fixed-point range (fixed_range)

  bool is_front(std::int32_t t) const { return front[static_cast<size_t>(t)] != 0; }

  /// The surface at the image point (px, py) (a sample's centre is (x + 0.5, y + 0.5)) on
  /// triangle t.
  Sample sample_at(double px, double py, std::int32_t t) const {
    const bool front_face = is_front(t);
    const Index i0 = F(t, 0), i1 = F(t, 1), i2 = F(t, 2);
    const Projected &p0 = P[i0], &p1 = P[i1], &p2 = P[i2];
    const double inv_area = 1.0 / area[static_cast<size_t>(t)];
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
      if (!(n.squaredNorm() > 0)) n = front_face ? Vec3(-forward) : Vec3(forward);  // degenerate in 3D
    }
    n.normalize();
    if (!front_face) n = -n;
    // Interpolated normals may turn away at silhouettes; keep them facing the viewer.
    const Vec3 view = perspective ? Vec3((camera.eye - (b0 * Vec3(V.row(i0)) + b1 * Vec3(V.row(i1)) +
                                                        b2 * Vec3(V.row(i2))))
                                             .normalized())
                                  : Vec3(-forward);
    if (n.dot(view) < 0) n = (n - 1.0 * n.dot(view) * view).normalized();
    return {n, b0 * vertex_colour(C, i0, uniform_colour) + b1 * vertex_colour(C, i1, uniform_colour) +
                   b2 * vertex_colour(C, i2, uniform_colour)};
  }
  /// The surface at the centre of the output pixel whose first sample is (x0, y0), on triangle t.
  Sample sample_at_pixel(int x0, int y0, int ss, std::int32_t t) const { return sample_at(x0 + 0.5 * ss, y0 + 0.5 * ss, t); }
  /// The colour of the surface point s of triangle t.
  Rgb lit(const Sample& s, std::int32_t t) const { return scale_rgb(shade(s.base, s.n, is_front(t), light, style)); }
  /// The colour of sample (x, y) on triangle t.
  Rgb shade_sample(int x, int y, std::int32_t t) const { return lit(sample_at(x + 0.5, y + 0.5, t), t); }

 private:
  void order_triangles(int w, int h);
};

/// The projected corners of the triangles in drawing order for a loop over k = 0, 1, 2, …,
/// gathered by a loop of their own (its loads are independent, so their cache misses overlap) for
/// the loop to read one after the other instead of chasing F and P from inside its longer body;
/// kGather triangles at a time, into a buffer that stays in the cache (not 72 bytes a triangle
/// for the whole mesh: 17 MB for the report's scan, written and read back through memory and
/// faulted in by each figure).
class CornerStream {
 public:
  explicit CornerStream(const SurfaceDraw& draw) : draw_(draw), corners_(std::min(draw.order.size(), kGather)) {}
  /// The corners of order[k]; k runs 0, 1, 2, … (each multiple of kGather gathers the next batch).
  const std::array<Projected, 3>& at(size_t k) {
    if (k % kGather == 0) gather(k);
    return corners_[k % kGather];
  }

 private:
  static constexpr size_t kGather = 2048;
  void gather(size_t first) {
    const size_t end = std::min(draw_.order.size(), first + kGather);
    for (size_t k = first; k < end; ++k) {
      const std::int32_t t = draw_.order[k];
      corners_[k - first] = {draw_.P[draw_.F(t, 0)], draw_.P[draw_.F(t, 1)], draw_.P[draw_.F(t, 2)]};
    }
  }
  const SurfaceDraw& draw_;
  std::vector<std::array<Projected, 3>> corners_;
};

}  // namespace breastfit::render::detail
