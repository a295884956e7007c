#include "breastfit/render/rasterizer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/adjacency.h"
#include "breastfit/render/detail/edge_refinement.h"
#include "breastfit/render/detail/raster_setup.h"
#include "breastfit/render/detail/shading.h"
#include "breastfit/render/detail/supersampled_surface.h"
#include "breastfit/render/detail/surface_draw.h"

namespace breastfit::render {

using detail::kEmpty;
using detail::pixel_index;
using detail::pixel_span;
using detail::scale_rgb;
using detail::Span;
using detail::to_vec;

namespace {

constexpr std::uint32_t kVisibleInk = std::numeric_limits<std::uint32_t>::max();

/// A point cloud (a mesh without faces) as shaded discs of `style.point_radius_px` output pixels
/// that write depth.
void splat_points(const Camera& camera, const Points& V, const Points& N, const Colors& C, const SurfaceStyle& style,
                  detail::SurfaceTarget& target) {
  const detail::Lighting light = detail::make_lighting(camera);
  const bool perspective = camera.projection == Projection::Perspective;
  const Vec3 f = camera.forward();
  const Vec3 uniform = to_vec(style.colour);
  const std::vector<Projected> P = camera.project_all(V, target.w, target.h);
  const double r = std::max(0.5, style.point_radius_px * target.ss);
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Projected& p = P[i];
    if (perspective && p.depth <= camera.near) continue;
    Vec3 n = N.rows() ? Vec3(N.row(i).transpose()) : Vec3(-f);
    bool front = true;
    if (n.squaredNorm() == 0) n = -f;
    n.normalize();
    if (n.dot(light.headlight) < 0) {
      n = -n;
      front = false;
    }
    const Rgb c = scale_rgb(detail::shade(detail::vertex_colour(C, static_cast<Index>(i), uniform), n, front, light, style));
    const Span xs = pixel_span(p.x - r, p.x + r, target.w), ys = pixel_span(p.y - r, p.y + r, target.h);
    if (!std::isfinite(p.depth)) continue;
    for (int y = ys.lo; y <= ys.hi; ++y)
      for (int x = xs.lo; x <= xs.hi; ++x) {
        const double dx = x + 0.5 - p.x, dy = y + 0.5 - p.y;
        if (dx * dx + dy * dy > r * r) continue;
        const size_t idx = static_cast<size_t>(y) * target.w + x;
        if (p.depth < target.depth[idx]) {
          target.depth[idx] = static_cast<float>(p.depth);
          target.colour.set(x, y, c);
        }
      }
  }
}

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
  detail::SurfaceTarget target{colour_, depth_, w_, h_, options_.width, options_.height, options_.supersample};
  if (F.rows() == 0) {
    splat_points(camera_, V, N, C, style, target);
    return;
  }
  const detail::SurfaceDraw draw(camera_, V, F, N, C, style, w_, h_);
  // Supersampling at the edges only needs empty buffers (the first surface drawn), an orthographic
  // view and every corner in the fixed-point range.
  if (options_.adaptive_supersample && options_.supersample > 1 && !draw.perspective && first_surface && draw.all_fixed)
    detail::draw_edge_refined(draw, target);
  else
    detail::draw_supersampled(draw, target);
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
