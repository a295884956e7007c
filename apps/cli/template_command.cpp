// `breastfit template`: inspect, build and pose rigged templates.
//   template info [FILE] [--json]     bones, blendshapes, landmarks, drawings, regions, counts
//   template build --out FILE         generate the default template and save it as glTF
//   template pose [--template FILE] --params P.json --out MESH
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/core/timer.h"
#include "breastfit/fit/surface_detail.h"
#include "breastfit/io/io.h"
#include "breastfit/model/gltf_io.h"
#include "breastfit/model/param_layout.h"
#include "breastfit/model/params_json.h"
#include "breastfit/model/pose_evaluator.h"
#include "breastfit/model/template_library.h"
#include "breastfit/template/default_template.h"
#include "commands.h"

namespace breastfit::cli {
namespace {

using json = nlohmann::json;

struct LoadedTemplate {
  std::filesystem::path path;
  model::RiggedModel model;
};

/// The surface detail a register params.json carries ("surface_detail": {"offsets_mm": [...]}),
/// or nullopt. \throws InvalidInput when it is malformed or not one offset per vertex.
std::optional<Eigen::VectorXd> read_surface_detail(const std::string& path, Index num_vertices) {
  std::ifstream f(path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(f);
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;  // read_params_json has already accepted the file: not JSON here cannot happen
  }
  if (!j.is_object() || !j.contains("surface_detail")) return std::nullopt;
  const auto& d = j["surface_detail"];
  if (!d.is_object() || !d.contains("offsets_mm") || !d["offsets_mm"].is_array())
    throw InvalidInput(path + ": \"surface_detail\" has no \"offsets_mm\" array");
  const auto& a = d["offsets_mm"];
  if (static_cast<Index>(a.size()) != num_vertices)
    throw InvalidInput(path + ": \"surface_detail\" has " + std::to_string(a.size()) + " offsets, the template " +
                       std::to_string(num_vertices) + " vertices (parameters of another template?)");
  Eigen::VectorXd out(num_vertices);
  for (Index i = 0; i < num_vertices; ++i) {
    if (!a[static_cast<size_t>(i)].is_number())
      throw InvalidInput(path + ": \"surface_detail\" offset " + std::to_string(i) + " is not a number");
    out[i] = a[static_cast<size_t>(i)].get<double>();
  }
  return out;
}

LoadedTemplate load(const std::string& file, const std::string& mesh = "") {
  LoadedTemplate t;
  t.path = file.empty() ? model::default_template_path() : std::filesystem::path(file);
  t.model = model::load_gltf(t.path, mesh);
  return t;
}

json vec(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

json info_json(const LoadedTemplate& t) {
  const model::RiggedModel& m = t.model;
  const model::ParamLayout layout(m);
  json bones = json::array();
  for (const auto& b : m.bones) {
    bones.push_back({{"name", b.name},
                     {"parent", b.parent ? json(m.bones[*b.parent].name) : json(nullptr)},
                     {"pivot_mm", vec(b.pivot)},
                     {"axes", json::array({vec(b.axes.col(0)), vec(b.axes.col(1)), vec(b.axes.col(2))})},
                     {"scale_lo", vec(b.scale_lo)},
                     {"scale_hi", vec(b.scale_hi)}});
  }
  json shapes = json::array();
  for (const auto& s : m.blendshapes) {
    double max_mm = 0;
    for (Index r = 0; r < s.displacements.rows(); ++r) max_mm = std::max(max_mm, s.displacements.row(r).norm());
    shapes.push_back({{"name", s.name},
                      {"lo", s.lo},
                      {"hi", s.hi},
                      {"num_vertices", s.vertices.size()},
                      {"max_displacement_mm", max_mm}});
  }
  json landmarks = json::array();
  for (const auto& l : m.landmarks)
    landmarks.push_back({{"name", l.name},
                         {"face", l.point.face},
                         {"bary", vec(l.point.bary)},
                         {"position_mm", vec(l.point.position(m.rest.V, m.rest.F))}});
  json drawings = json::array();
  for (const auto& d : m.drawings)
    drawings.push_back({{"name", d.name}, {"closed", d.closed}, {"num_points", d.points.size()}});
  json regions = json::array();
  for (const auto& r : m.regions) regions.push_back({{"name", r.name}, {"num_vertices", r.vertices.size()}});
  json params = json::array();
  for (int q = 0; q < layout.num_params(); ++q) params.push_back(layout.name(q));
  return json{{"name", m.name},
              {"path", t.path.string()},
              {"num_vertices", m.num_vertices()},
              {"num_faces", m.rest.num_faces()},
              {"num_bones", m.num_bones()},
              {"num_blendshapes", m.num_blendshapes()},
              {"num_landmarks", m.landmarks.size()},
              {"num_drawings", m.drawings.size()},
              {"num_regions", m.regions.size()},
              {"num_params", layout.num_params()},
              {"bones", bones},
              {"blendshapes", shapes},
              {"landmarks", landmarks},
              {"drawings", drawings},
              {"regions", regions},
              {"parameters", params}};
}

std::string fmt_vec(const Vec3& v, int precision = 1) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.*f, %.*f, %.*f)", precision, v.x(), precision, v.y(), precision, v.z());
  return buf;
}

void print_info(std::ostream& os, const LoadedTemplate& t) {
  const model::RiggedModel& m = t.model;
  const model::ParamLayout layout(m);
  os << "template '" << m.name << "' (" << t.path.string() << ")\n";
  os << "  " << m.num_vertices() << " vertices, " << m.rest.num_faces() << " faces, " << layout.num_params()
     << " parameters (7 global + 9 x " << m.num_bones() << " bones + " << m.num_blendshapes() << " blendshapes)\n";
  os << "bones (" << m.num_bones() << "):\n";
  for (const auto& b : m.bones) {
    char line[256];
    std::snprintf(line, sizeof line, "  %-20s parent %-16s pivot %s mm  scale lo %s hi %s\n", b.name.c_str(),
                  b.parent ? m.bones[*b.parent].name.c_str() : "-", fmt_vec(b.pivot).c_str(),
                  fmt_vec(b.scale_lo, 2).c_str(), fmt_vec(b.scale_hi, 2).c_str());
    os << line;
  }
  os << "blendshapes (" << m.num_blendshapes() << "):\n";
  for (const auto& s : m.blendshapes) {
    char line[256];
    std::snprintf(line, sizeof line, "  %-28s [%g, %g]  moves %zu vertices\n", s.name.c_str(), s.lo, s.hi,
                  s.vertices.size());
    os << line;
  }
  os << "landmarks (" << m.landmarks.size() << "):\n";
  for (const auto& l : m.landmarks)
    os << "  " << l.name << "  at " << fmt_vec(l.point.position(m.rest.V, m.rest.F)) << " mm (face " << l.point.face
       << ")\n";
  os << "drawings (" << m.drawings.size() << "):\n";
  for (const auto& d : m.drawings)
    os << "  " << d.name << "  " << (d.closed ? "closed" : "open") << ", " << d.points.size() << " points\n";
  os << "regions (" << m.regions.size() << "):\n";
  for (const auto& r : m.regions) os << "  " << r.name << "  " << r.vertices.size() << " vertices\n";
}

}  // namespace

void register_template(CLI::App& app, int& exit_code) {
  auto* sub = app.add_subcommand("template", "Inspect, build and pose rigged templates (glTF)");
  sub->require_subcommand(1);

  // template info
  struct InfoArgs {
    std::string file, mesh;
    bool json = false;
  };
  auto info_args = std::make_shared<InfoArgs>();
  auto* info = sub->add_subcommand("info", "List a template's bones, blendshapes, landmarks, drawings and counts");
  info->add_option("file", info_args->file, "template .gltf/.glb (default: the shipped default template)");
  info->add_flag("--json", info_args->json, "print a JSON object instead of text");
  info->add_option("--mesh", info_args->mesh, "the skinned mesh to read when the file has several (its node or mesh name)");
  info->callback([info_args] {
    const LoadedTemplate t = load(info_args->file, info_args->mesh);
    if (info_args->json) std::cout << info_json(t).dump(2) << "\n";
    else print_info(std::cout, t);
  });

  // template build
  struct BuildArgs {
    std::string out;
    double edge_mm = templ::DefaultTemplateOptions{}.target_edge_mm;
  };
  auto build_args = std::make_shared<BuildArgs>();
  auto* build = sub->add_subcommand("build", "Generate the default template and save it as glTF (.gltf or .glb)");
  build->add_option("--out,-o", build_args->out, "output file (.gltf or .glb)")->required();
  build->add_option("--edge-mm", build_args->edge_mm, "target edge length of the remeshed surface (mm)");
  build->callback([build_args] {
    Timer timer;
    templ::DefaultTemplateOptions options;
    options.target_edge_mm = build_args->edge_mm;
    const model::RiggedModel m = templ::build_default_template(options);
    model::save_gltf(build_args->out, m);
    std::cout << "wrote " << build_args->out << ": " << m.num_vertices() << " vertices, " << m.rest.num_faces()
              << " faces, " << m.num_bones() << " bones, " << m.num_blendshapes() << " blendshapes, "
              << m.landmarks.size() << " landmarks, " << m.drawings.size() << " drawings ("
              << static_cast<int>(timer.seconds() * 1000) << " ms)\n";
  });

  // template pose
  struct PoseArgs {
    std::string templ, templ_mesh, params, out;
    bool no_detail = false;
  };
  auto pose_args = std::make_shared<PoseArgs>();
  auto* pose = sub->add_subcommand("pose", "Pose a template with parameters from a JSON file and write the mesh");
  pose->add_option("--template,-t", pose_args->templ, "template .gltf/.glb (default: the shipped default template)");
  pose->add_option("--params", pose_args->params,
                   "JSON object of parameter values by name, any subset (see `template info --json`)")
      ->required();
  pose->add_option("--out,-o", pose_args->out, "output mesh (.ply, .obj, .stl or .vtk), mm")->required();
  pose->add_option("--mesh", pose_args->templ_mesh, "the skinned mesh to pose when the file has several (node or mesh name)");
  pose->add_flag("--no-detail", pose_args->no_detail,
                 "ignore the surface detail of a register params.json (the posed template alone; by default the "
                 "offsets are applied, so the mesh is register's fitted.ply)");
  pose->callback([pose_args] {
    const LoadedTemplate t = load(pose_args->templ, pose_args->templ_mesh);
    const model::PoseParams p = model::read_params_json(pose_args->params, t.model);
    TriangleMesh mesh;
    mesh.V = model::pose_vertices(t.model, p);
    mesh.F = t.model.rest.F;
    const std::optional<Eigen::VectorXd> detail = read_surface_detail(pose_args->params, mesh.num_vertices());
    if (detail && !pose_args->no_detail) mesh.V = fit::apply_surface_detail(mesh.V, mesh.F, *detail);
    io::write_mesh(pose_args->out, mesh);
    std::cout << "wrote " << pose_args->out << ": " << mesh.num_vertices() << " vertices, " << mesh.num_faces()
              << " faces (mm); "
              << (!detail ? "no surface detail in the parameters: the posed template"
                  : pose_args->no_detail ? "surface detail of the parameters NOT applied (--no-detail): the posed template"
                                         : "surface detail applied: register's fitted surface")
              << "\n";
  });
  (void)exit_code;
}

}  // namespace breastfit::cli
