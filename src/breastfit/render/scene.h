#pragma once
/// \file One-call rendering of a scene (meshes, curves, labelled points) from a standard torso
/// view to an image, with optional title, colour bar, legend and orientation markers.
///
/// Example:
/// \code
///   render::Scene scene;
///   scene.meshes.push_back({.name = "scan", .mesh = scan});
///   scene.points.push_back({.label = "nipple_R", .position = p});
///   render::RenderOptions opt;
///   opt.view = render::View::Front;
///   opt.body_to_world = mesh::estimate_body_frame(scan, landmarks).body_to_world;
///   render::render_scene(scene, opt).save_png("front.png");
/// \endcode
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/render/camera.h"
#include "breastfit/render/colormap.h"
#include "breastfit/render/image.h"
#include "breastfit/render/rasterizer.h"
#include "breastfit/render/view.h"

namespace breastfit::render {

/// Per-vertex values shown through a colour map (with a colour bar).
struct ScalarField {
  Eigen::VectorXd values;          ///< #V values; NaN = no value (drawn grey)
  Colormap map = Colormap::Viridis;
  std::optional<double> lo;        ///< value mapped to the start; default: min of finite values
  std::optional<double> hi;        ///< value mapped to the end; default: max of finite values
  std::string units = "mm";        ///< colour-bar units label
  std::string label;               ///< colour-bar quantity name, e.g. "distance"
};

struct SceneMesh {
  std::string name;
  TriangleMesh mesh;                   ///< a triangle mesh, or a point cloud (no faces)
  SurfaceStyle style;                  ///< shading; style.colour is the uniform colour
  bool use_vertex_colours = true;      ///< use mesh.C when present (else style.colour)
  std::optional<ScalarField> scalars;  ///< overrides the colours when set
  bool wireframe = false;              ///< overlay the edges
  WireframeStyle wireframe_style;
};

struct ScenePolyline {
  std::string name;        ///< shown in the legend when not empty
  Points points;           ///< N by 3
  bool closed = false;
  Rgb colour = {20, 90, 200};
  double width_px = 3.0;   ///< output pixels
};

struct ScenePoint {
  std::string label;       ///< drawn next to the point when not empty
  Vec3 position = Vec3::Zero();
  Rgb colour = {220, 30, 30};
  double radius_px = 6.0;  ///< disc radius in output pixels (or world units, see radius_unit)
  SizeUnit radius_unit = SizeUnit::Pixels;  ///< World: radius_px is in world units (mm) instead
};

struct Scene {
  std::vector<SceneMesh> meshes;
  std::vector<ScenePolyline> polylines;
  std::vector<ScenePoint> points;

  /// Bounding box of every mesh vertex, polyline point and point (empty box when none).
  Eigen::AlignedBox3d bounds() const;
};

struct RenderOptions {
  View view = View::Front;
  /// Body frame (LPS: x = patient's left, y = posterior, z = superior) → world (the scene's
  /// coordinates). Identity for data already in the body frame (the template).
  Eigen::Matrix4d body_to_world = Eigen::Matrix4d::Identity();
  int width = 1024;                    ///< pixels
  int height = 1024;                   ///< pixels
  Rgb background = {255, 255, 255};
  Projection projection = Projection::Orthographic;
  double fov_y_deg = 30.0;             ///< perspective only
  double margin = 0.06;                ///< free border around the framed scene, fraction of size
  int supersample = 2;                 ///< anti-aliasing factor, 1..4
  /// Overlays up to this far behind the surface count as visible (world units); default 1 % of
  /// the scene's bounding-box diagonal (≈ 6 mm for a torso), enough for curves on noisy skin.
  std::optional<double> depth_bias;
  bool show_hidden = true;             ///< draw hidden curves/points dimmed (else omit them)
  double hidden_alpha = 0.3;           ///< opacity of hidden overlays
  bool show_labels = true;             ///< point labels
  bool show_legend = true;             ///< named polylines listed along the bottom, kept clear of the scene
  bool show_colorbar = true;           ///< when a mesh has scalars
  bool show_orientation = true;        ///< R/L (or A/P) letters at the image sides
  std::string title;                   ///< top-left caption line; empty = none
  /// Bottom-right caption (with show_orientation); default "<view name> view". Say when the
  /// orientation is not known, e.g. "view: orientation unknown".
  std::optional<std::string> view_caption;
  int text_scale = 0;                  ///< font scale; 0 = automatic (1 per 512 px of the smaller side)
  std::optional<Camera> camera;        ///< overrides the view and the framing
  std::optional<Eigen::AlignedBox3d> frame;  ///< region to frame; default: Scene::bounds()

  /// \throws InvalidInput naming the offending field.
  void validate() const;
};

/// The camera render_scene uses (the options' camera, or the view framing the scene).
/// \throws InvalidInput if there is nothing to frame.
Camera scene_camera(const Scene& scene, const RenderOptions& options);

/// The legend's box in image pixels ([min, max) corners), or nullopt without a legend. The
/// framing (scene_camera) keeps the scene out of it: the legend never covers the body.
std::optional<Eigen::AlignedBox2i> legend_box(const Scene& scene, const RenderOptions& options);

/// The first of render_scene's two passes: a Rasterizer with the camera scene_camera chooses
/// and the scene's meshes drawn (shaded, depth buffer filled), nothing else. It may be made
/// ahead of the rest (e.g. on another thread) from a scene holding only the meshes and what
/// the framing needs (polylines without points still reserve their legend entries).
/// \throws InvalidInput as render_scene.
Rasterizer draw_scene_meshes(const Scene& scene, const RenderOptions& options);

/// The second pass: the scene's wireframes, polylines and points depth-tested against
/// `raster`'s meshes, then the anti-aliased image with the colour bar, legend, labels,
/// orientation letters and title. The camera is `raster`'s; `scene` need not repeat the meshes
/// (only those with a wireframe or scalars matter here).
/// render_scene(s, o) == finish_scene(draw_scene_meshes(s, o), s, o).
/// \throws InvalidInput for invalid options.
Image finish_scene(Rasterizer raster, const Scene& scene, const RenderOptions& options);

/// Renders the scene. Deterministic: the same inputs give identical pixels (and PNG bytes).
/// \throws InvalidInput for invalid options, mismatched scalar/colour sizes or an empty scene.
Image render_scene(const Scene& scene, const RenderOptions& options = {});

}  // namespace breastfit::render
