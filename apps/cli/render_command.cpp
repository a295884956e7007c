// `breastfit render`: headless PNG views of a mesh (with landmarks and drawings) or of a rigged
// template. See docs/RENDER.md.
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/io/landmarks_io.h"
#include "breastfit/io/markups.h"
#include "breastfit/io/output_set.h"
#include "breastfit/mesh/units.h"
#include "breastfit/model/gltf_io.h"
#include "breastfit/model/template_library.h"
#include "breastfit/mesh/body_frame.h"
#include "breastfit/fit/orientation_search.h"
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/render/scene.h"
#include "breastfit/render/torso_overlays.h"
#include "breastfit/template/default_template.h"
#include "command_support.h"
#include "commands.h"
#include "file_warnings.h"

namespace breastfit::cli {

namespace {

namespace fs = std::filesystem;

struct RenderArgs {
  std::string mesh;
  std::string template_file, template_mesh;
  bool use_template = false;
  std::string landmarks;
  std::string placed;
  std::string drawings;
  std::string view = "front";
  int size = 1024;
  std::string title;
  std::string out;
  std::string frame = "auto";
  std::string units = "auto";
  bool wireframe = false;
  bool no_labels = false;
  bool no_hidden = false;
  bool force = false;
};

bool ends_with_png(const std::string& s) {
  if (s.size() < 4) return false;
  std::string ext = s.substr(s.size() - 4);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png";
}

/// Output path of one view: the exact file for a single view given as *.png, else PREFIX_view.png.
fs::path output_path(const std::string& out, render::View view, bool single) {
  if (single && ends_with_png(out)) return fs::path(out);
  const std::string prefix = ends_with_png(out) ? out.substr(0, out.size() - 4) : out;
  return fs::path(prefix + "_" + std::string(render::view_name(view)) + ".png");
}

using render::add_curve;
using render::landmark_point;
using render::OverlaySizes;

/// The landmarks of a file in the scene's units (declared units converted; undeclared: taken as
/// the scene's units).
std::vector<NamedPoint> read_scene_landmarks(const std::string& path, std::optional<mesh::Units> scene_units) {
  io::LandmarkReadOptions opt;
  opt.require_known_names = false;
  LandmarkSet lm = read_landmarks_warning(path, opt);
  // Bring declared units to the scene's units (undeclared: assume the scene's units).
  double factor = 1.0;
  if (lm.declared_units && scene_units) {
    const double declared_mm = *lm.declared_units == "m" ? 1000.0 : 1.0;
    factor = declared_mm / mesh::to_mm_factor(*scene_units);
  }
  for (NamedPoint& p : lm.points) p.position *= factor;
  return lm.points;
}

/// Adds the landmarks of --landmarks (red, labelled) and of --placed (dark, joined to the
/// same-named --landmarks point by a line).
void add_landmarks(render::Scene& scene, mesh::NamedPositions& named, const RenderArgs& a,
                   std::optional<mesh::Units> scene_units, const OverlaySizes& sizes) {
  std::vector<NamedPoint> fitted;
  if (!a.landmarks.empty()) fitted = read_scene_landmarks(a.landmarks, scene_units);
  if (!a.placed.empty()) render::add_placed_landmarks(scene, read_scene_landmarks(a.placed, scene_units), fitted, sizes);
  for (const NamedPoint& p : fitted) {
    scene.points.push_back(landmark_point(p.name, p.position, sizes));
    named[p.name] = p.position;
  }
}

/// Adds the curves (and points) of a markups file; read_markups gives millimetres.
void add_drawings(render::Scene& scene, const std::string& path, std::optional<mesh::Units> scene_units,
                  const OverlaySizes& sizes) {
  const Markups m = read_markups_warning(path).markups;
  const double factor = scene_units ? 1.0 / mesh::to_mm_factor(*scene_units) : 1.0;
  for (const Curve& c : m.curves) add_curve(scene, c.name, c.closed, factor * c.points, sizes);
  for (const NamedPoint& p : m.points) {
    render::ScenePoint sp = landmark_point(p.name, factor * p.position, sizes);
    sp.colour = {30, 30, 30};
    sp.radius_px = 0.7 * sizes.point_radius_px;
    scene.points.push_back(sp);
  }
}

/// The shipped default template (model::default_template_path(): $BREASTFIT_TEMPLATE, installed
/// or source-tree default_torso.glb); when none is shipped and $BREASTFIT_TEMPLATE is not set,
/// the template built in memory by templ::build_default_template().
model::RiggedModel default_template(std::string& what) {
  const char* env = std::getenv("BREASTFIT_TEMPLATE");
  if (env && *env) {
    what = fs::path(env).filename().string();
    return model::load_default_template();  // an explicit choice: no fallback
  }
  std::optional<fs::path> shipped;
  try {
    shipped = model::default_template_path();
  } catch (const IoError&) {
    shipped.reset();
  }
  if (shipped) {
    what = "default template (" + shipped->filename().string() + ")";
    return model::load_gltf(*shipped);
  }
  what = "default template (built)";
  return templ::build_default_template();
}

/// The body frame of a torso scan without landmarks, from its geometry: the landmark-free
/// orientation search of `register` (the default template fitted in every turn of the shape's
/// axes, fit/orientation_search.h). nullopt when the scan is not a plausible torso or the best
/// orientation is not clearly better than a different one (then front and back are not known).
std::optional<mesh::BodyFrame> body_frame_from_geometry(const TriangleMesh& mesh, mesh::Units units,
                                                        std::string& note) {
  try {
    const fit::FitOptions options;
    pipeline::PreparedTarget target = pipeline::prepare_target(mesh, "mesh", units, options);
    std::string what;
    const model::RiggedModel model = default_template(what);
    const fit::OrientationSearch search = fit::search_orientation(model, *target.target, options);
    char margin[32];
    std::snprintf(margin, sizeof margin, "%.0f", 100 * search.margin);
    if (search.hypotheses.empty() || search.margin < options.orientation_min_margin) {
      note = "orientation unknown: the template fits '" + search.runner_up + "' almost as well as the best turn (" +
             margin + " % margin)";
      return std::nullopt;
    }
    // The template is in the body frame: its placement on the scan is body → scan (mm → file units).
    const double to_file = 1.0 / mesh::to_mm_factor(units);
    mesh::BodyFrame bf;
    bf.body_to_world.topLeftCorner<3, 3>() = search.params.global.rotation.toRotationMatrix();
    bf.body_to_world.topRightCorner<3, 1>() = to_file * search.params.global.translation;
    bf.source = mesh::BodyFrameSource::PrincipalAxes;
    bf.description = "the scan's geometry (template orientation search: '" + search.hypotheses.front().name + "', " +
                     margin + " % better than '" + search.runner_up + "')";
    return bf;
  } catch (const InvalidInput& e) {  // not a plausible torso scan (size, shape)
    note = std::string("orientation unknown: ") + e.what();
    return std::nullopt;
  } catch (const IoError& e) {  // no template to search with
    note = std::string("orientation unknown: ") + e.what();
    return std::nullopt;
  }
}

void run_render(const RenderArgs& a) {
  if (a.out.empty()) throw InvalidInput("render: --out is required");
  if (a.size < 16 || a.size > 8192) throw InvalidInput("render: --size must be in [16, 8192], got " + std::to_string(a.size));
  if (a.use_template == !a.mesh.empty())
    throw InvalidInput("render: give either a MESH file or --template [FILE], not both / neither");
  if (!a.template_mesh.empty() && !a.use_template) throw InvalidInput("render: --mesh NAME chooses a template's mesh: give --template too");
  if (a.frame != "auto" && a.frame != "landmarks" && a.frame != "axes" && a.frame != "identity")
    throw InvalidInput("render: --frame must be auto, landmarks, axes or identity, got '" + a.frame + "'");
  const OverlaySizes sizes(a.size);
  std::vector<render::View> views;
  if (a.view == "all")
    views = render::default_views();
  else
    views = {render::view_from_name(a.view)};

  render::Scene scene;
  mesh::NamedPositions named;
  std::string what;
  Eigen::Matrix4d body_to_world = Eigen::Matrix4d::Identity();
  std::string frame_note = "body frame (identity)";
  bool orientation_known = true;
  std::optional<mesh::Units> mesh_units;

  if (a.use_template) {
    model::RiggedModel model;
    if (!a.template_file.empty() || !a.template_mesh.empty()) {
      model = load_template(a.template_file, a.template_mesh);
      what = a.template_file.empty() ? "default template" : fs::path(a.template_file).filename().string();
      if (!a.template_mesh.empty()) what += " (mesh " + a.template_mesh + ")";
    } else {
      model = default_template(what);
    }
    scene.meshes.emplace_back();
    scene.meshes.back().name = model.name;
    scene.meshes.back().mesh = model.rest;
    scene.meshes.back().wireframe = a.wireframe;
    for (const model::Drawing& d : model.drawings) {
      Points P(static_cast<Eigen::Index>(d.points.size()), 3);
      for (size_t i = 0; i < d.points.size(); ++i)
        P.row(static_cast<Eigen::Index>(i)) = d.points[i].position(model.rest.V, model.rest.F).transpose();
      add_curve(scene, d.name, d.closed, P, sizes);
    }
    for (const model::ModelLandmark& l : model.landmarks) {
      const Vec3 p = l.point.position(model.rest.V, model.rest.F);
      scene.points.push_back(landmark_point(l.name, p, sizes));
      named[l.name] = p;
    }
    // The template is in millimetres, in the body frame.
    add_landmarks(scene, named, a, mesh::Units::Millimetres, sizes);
    if (!a.drawings.empty()) add_drawings(scene, a.drawings, mesh::Units::Millimetres, sizes);
  } else {
    TriangleMesh mesh = io::read_mesh(a.mesh);
    what = fs::path(a.mesh).filename().string();
    // Units only matter to bring declared-unit markups to the mesh's units; an ambiguous mesh
    // (not torso-sized) is taken as millimetres unless --units says otherwise.
    std::optional<mesh::Units> units = mesh::parse_units(a.units);
    if (!units) {
      try {
        units = mesh::detect_units(mesh.V);
      } catch (const InvalidInput&) {
        units = mesh::Units::Millimetres;
      }
    }
    mesh_units = units;
    scene.meshes.emplace_back();
    scene.meshes.back().name = what;
    scene.meshes.back().mesh = std::move(mesh);
    scene.meshes.back().wireframe = a.wireframe;
    add_landmarks(scene, named, a, units, sizes);
    if (!a.drawings.empty()) add_drawings(scene, a.drawings, units, sizes);
  }

  // The view frame: the template is in the body frame already; a scan is in a scanner frame.
  const std::string frame_mode = a.frame == "auto" ? (a.use_template ? "identity" : "estimate") : a.frame;
  if (frame_mode == "estimate" || frame_mode == "landmarks" || frame_mode == "axes") {
    std::optional<mesh::BodyFrame> bf;
    if (frame_mode != "axes") bf = mesh::body_frame_from_landmarks(named);
    if (!bf && frame_mode == "landmarks")
      throw InvalidInput("render: --frame landmarks needs sternal_notch/xiphoid (or acromions with breasts) "
                         "and a left/right pair (acromion, midaxillary, pectoral_insertion, nipple or lowest_breast)");
    // No landmark frame: the scan's geometry (auto), else the principal axes, whose front/back
    // and up/down are guesses — the views are then captioned as of unknown orientation.
    std::string unknown;
    if (!bf && frame_mode == "estimate" && mesh_units) bf = body_frame_from_geometry(scene.meshes.front().mesh, *mesh_units, unknown);
    if (!bf) {
      bf = mesh::body_frame_from_principal_axes(scene.meshes.front().mesh);
      orientation_known = false;
      if (unknown.empty()) unknown = "orientation unknown: the principal axes do not tell front from back";
    }
    body_to_world = bf->body_to_world;
    frame_note = "body frame from " + bf->description + (orientation_known ? "" : "; " + unknown);
  }

  render::RenderOptions opt;
  opt.width = a.size;
  opt.height = a.size;
  opt.body_to_world = body_to_world;
  opt.show_labels = !a.no_labels;
  opt.show_hidden = !a.no_hidden;
  std::vector<fs::path> paths;  // written as one set: all views or none (io/output_set.h)
  for (render::View v : views) paths.push_back(output_path(a.out, v, views.size() == 1));
  for (const fs::path& p : paths)
    check_output_file(p.string(), {a.mesh, a.template_file, a.landmarks, a.placed, a.drawings}, a.force);
  io::OutputSet set = io::loose_file_set(paths);
  for (size_t k = 0; k < views.size(); ++k) {
    opt.view = views[k];
    opt.title = a.title.empty() ? what : a.title;
    if (!orientation_known) opt.view_caption = "view: orientation unknown";
    render::render_scene(scene, opt).save_png(set.path(paths[k].filename().string()));
  }
  set.commit();
  for (size_t k = 0; k < views.size(); ++k)
    std::cout << "wrote " << paths[k].string() << " (" << render::view_name(views[k]) << ", " << a.size << "x" << a.size
              << ")\n";
  std::cout << frame_note << "\n";
}

}  // namespace

void register_render(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RenderArgs>();
  auto* sub = app.add_subcommand("render", "Render a mesh (with landmarks and drawings) or a template to PNG");
  sub->add_option("mesh", args->mesh, "Mesh file (.ply, .obj, .stl, .vtk, .vtp); omit with --template");
  auto* tpl = sub->add_option("--template,-t", args->template_file,
                              "Render a rigged template (.gltf/.glb) with its landmarks and drawings on the rest "
                              "mesh; without FILE the built-in default template")
                  ->expected(0, 1);
  sub->add_option("--mesh", args->template_mesh, "with --template: " "the template's skinned mesh to use when its file has several (node or mesh name)");
  sub->add_option("--landmarks,-l", args->landmarks, "Landmarks to draw (.mrk.json, .json, .csv)");
  sub->add_option("--placed", args->placed,
                  "Landmarks a person placed (e.g. register's input), drawn dark beside --landmarks (e.g. "
                  "register's landmarks.mrk.json, red) with a line between same-named points");
  sub->add_option("--drawings", args->drawings, "Curves to draw (Slicer .mrk.json)");
  sub->add_option("--view", args->view,
                  "front, side (the patient's right), side-left, oblique (front-right), oblique-left, back, top, or "
                  "all (= front, side, side-left, oblique, oblique-left)")
      ->capture_default_str();
  sub->add_option("--size", args->size, "Image width and height in pixels")->capture_default_str();
  sub->add_option("--title", args->title, "Caption line (default: the input's file name)");
  sub->add_option("--out,-o", args->out, "Output PNG, or prefix: PREFIX_<view>.png")->required();
  sub->add_option("--frame", args->frame,
                  "View frame: auto (template: identity; mesh: landmarks, else the scan's geometry by the "
                  "template orientation search, else 'orientation unknown'), landmarks, axes (principal axes: "
                  "views captioned 'orientation unknown'), identity")
      ->capture_default_str();
  sub->add_option("--units", args->units, "Mesh units for declared-unit markups: auto, mm or m")->capture_default_str();
  sub->add_flag("--wireframe", args->wireframe, "Overlay the mesh edges");
  sub->add_flag("--no-labels", args->no_labels, "Do not draw landmark names");
  sub->add_flag("--no-hidden", args->no_hidden, "Omit hidden landmarks and curve parts (default: dimmed)");
  sub->add_flag("--force", args->force, "replace existing output images");
  // Outcomes are exceptions (mapped by main.cpp); exit_code stays kExitOk on success.
  (void)exit_code;
  sub->callback([args, tpl] {
    args->use_template = tpl->count() > 0;
    run_render(*args);
  });
}

}  // namespace breastfit::cli
