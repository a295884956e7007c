#pragma once
/// \file A deterministic, single-threaded z-buffer software rasterizer: shaded triangle meshes
/// (or point clouds) with overlays (polylines, points, wireframes) depth-tested against them.
/// Renders at `supersample`× the output size and box-filters down (anti-aliasing).
#include <cstdint>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/render/camera.h"
#include "breastfit/render/image.h"

namespace breastfit::render {

/// Output size, anti-aliasing and overlay visibility rules.
struct RasterOptions {
  int width = 1024;                 ///< output image width, pixels
  int height = 1024;                ///< output image height, pixels
  int supersample = 2;              ///< internal resolution factor (1 = no anti-aliasing), 1..4
  /// Supersample only the output pixels at an edge (a change of coverage or facing, a jump of
  /// depth: silhouettes, folds, holes), the others lit once at their centre: the first draw_mesh
  /// of an orthographic view (later meshes, perspective views and point clouds always take the
  /// full path). About half the cost of a dense mesh's surface; false = every sample.
  bool adaptive_supersample = true;
  Rgb background = {255, 255, 255};
  /// World units an overlay may lie behind the surface and still count as visible (curves drawn
  /// on noisy skin); 0 = strict depth test. Larger shows more but lets things shine through.
  double depth_bias = 0.0;
  bool show_hidden_overlays = true;  ///< draw hidden overlay parts dimmed (else skip them)
  double hidden_alpha = 0.3;         ///< opacity of hidden overlay parts, in (0, 1]

  /// \throws InvalidInput naming the offending field.
  void validate() const;
};

/// How a surface is shaded: per-pixel (Phong) lighting with a headlight and a key light from the
/// upper left of the viewer; back faces (the inside of an open scan) get a darker, cooler tint.
struct SurfaceStyle {
  Rgb colour = {224, 186, 162};  ///< base colour when no per-vertex colours are given (skin tone)
  Rgb back_colour = {150, 158, 176};  ///< base colour of back faces
  double ambient = 0.28;         ///< ambient light, [0, 1]
  double headlight = 0.50;       ///< diffuse weight of the light at the camera
  double key_light = 0.32;       ///< diffuse weight of the light from the upper left
  double specular = 0.10;        ///< Blinn-Phong highlight weight (headlight), [0, 1]
  double shininess = 24.0;       ///< highlight exponent
  double back_brightness = 0.75;  ///< brightness factor applied to back faces
  bool smooth = true;            ///< interpolate vertex normals (false = flat faces)
  double point_radius_px = 1.5;  ///< splat radius for point clouds (no faces), output pixels
};

/// A polyline overlay. Width in output pixels.
struct LineStyle {
  Rgb colour = {20, 90, 200};
  double width_px = 3.0;
};

enum class SizeUnit { Pixels, World };

/// A point overlay drawn as a shaded disc with a dark rim.
struct PointStyle {
  Rgb colour = {220, 30, 30};
  double radius = 6.0;            ///< disc radius, in `unit`
  SizeUnit unit = SizeUnit::Pixels;  ///< output pixels, or world units (mm) at the point's depth
};

/// A wireframe overlay (the mesh edges, once each, blended over the surface).
struct WireframeStyle {
  Rgb colour = {40, 40, 40};
  double alpha = 0.45;     ///< opacity in (0, 1]
  double width_px = 1.0;   ///< output pixels
};

class Rasterizer {
 public:
  /// \throws InvalidInput if the camera or the options are invalid.
  Rasterizer(const Camera& camera, const RasterOptions& options);

  /// Draws a mesh into the colour and depth buffers. Perspective: triangles reaching behind the
  /// near plane are skipped (no clipping; frame the scene instead). Non-finite vertices skip
  /// their triangles.
  /// \param V #V by 3 positions; \param F #F by 3 triangles (empty: V is splatted as points);
  /// \param N #V by 3 normals or empty (then area-weighted face normals are used);
  /// \param C #V by 3 colours or empty (then style.colour).
  /// \throws InvalidInput on size mismatches or out-of-range indices.
  void draw_mesh(const Points& V, const Triangles& F, const Points& N, const Colors& C,
                 const SurfaceStyle& style = {});
  /// draw_mesh with the mesh's own normals and colours.
  void draw_mesh(const TriangleMesh& mesh, const SurfaceStyle& style = {});

  /// Overlays: drawn over the surface, depth-tested against everything drawn with draw_mesh so
  /// far (draw them after all meshes). Hidden parts are dimmed or skipped (RasterOptions).
  void draw_polyline(const Points& P, bool closed, const LineStyle& style = {});
  void draw_point(const Vec3& p, const PointStyle& style = {});
  void draw_wireframe(const Points& V, const Triangles& F, const WireframeStyle& style = {});

  /// Output-image pixel coordinates and depth of a world point.
  Projected project(const Vec3& p) const;
  /// True when the point is in the image and not behind the surface (with the depth bias).
  bool is_visible(const Vec3& p) const;
  /// Fraction of output-image pixels covered by mesh surface, [0, 1].
  double surface_coverage() const;

  /// The anti-aliased output image (width × height).
  Image resolve() const;

  const Camera& camera() const { return camera_; }
  const RasterOptions& options() const { return options_; }

 private:
  Projected project_internal(const Vec3& p) const;
  bool overlay_visible_at(int x, int y, double depth) const;
  void paint_overlay(int x, int y, Rgb colour, bool visible, double alpha, bool allow_hidden);
  void draw_segment(const Projected& a, const Projected& b, double radius, Rgb colour, double alpha,
                    bool allow_hidden);
  void next_call();

  Camera camera_;
  RasterOptions options_;
  int w_ = 0;  // internal (supersampled) size
  int h_ = 0;
  Image colour_;
  std::vector<float> depth_;        // +inf where empty
  std::vector<std::uint32_t> ink_;  // overlay marks: 0 none, kVisibleInk, else the draw call id (allocated on first use)
  std::uint32_t call_id_ = 0;
  bool surface_drawn_ = false;  // a draw_mesh has written depth (the adaptive path needs empty buffers)
};

}  // namespace breastfit::render
