// `breastfit inspect FILE [--json] [--units auto|mm|m]`: what is in a mesh, point cloud,
// landmark or markups file (counts, bounding box, edges, borders, components, units guess;
// points and curves).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/io/landmarks_io.h"
#include "breastfit/io/markups.h"
#include "breastfit/mesh/landmark_names.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/mesh/mesh_stats.h"
#include "breastfit/mesh/units.h"
#include "commands.h"
#include "file_warnings.h"

namespace breastfit::cli {
namespace {

using nlohmann::ordered_json;

struct InspectArgs {
  std::string file;
  bool json = false;
  std::string units = "auto";
};

enum class FileKind { Mesh, Markups, Landmarks };

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

FileKind kind_of(const std::filesystem::path& path) {
  const std::string name = lower(path.filename().string());
  if (ends_with(name, ".mrk.json")) return FileKind::Markups;
  if (ends_with(name, ".json")) {
    // A plain .json holding a "markups" array is a markups file (with its curves).
    std::ifstream in(path, std::ios::binary);
    const nlohmann::json doc = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (doc.is_object() && doc.contains("markups")) return FileKind::Markups;
    return FileKind::Landmarks;
  }
  if (ends_with(name, ".csv") || ends_with(name, ".fcsv")) return FileKind::Landmarks;
  if (io::has_mesh_extension(path)) return FileKind::Mesh;
  const std::string ext = path.extension().string();
  throw IoError(path.string(), (ext.empty() ? std::string("no file extension") : "unknown extension '" + ext + "'") +
                                   " (supported: meshes " +
                                   std::string(io::kMeshExtensions) + "; landmarks and markups " +
                                   std::string(io::kLandmarkExtensions) + ")");
}

std::string num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

std::string vec(const Vec3& v) { return "(" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + ")"; }

ordered_json vec_json(const Vec3& v) { return ordered_json::array({v.x(), v.y(), v.z()}); }

// ---------------------------------------------------------------------------------------- mesh

void inspect_mesh(const InspectArgs& a, std::optional<mesh::Units> units) {
  const TriangleMesh m = io::read_mesh(a.file);
  const mesh::MeshStats s = mesh::mesh_stats(m, units);
  if (!a.json) {
    std::cout << "file: " << a.file << "\n" << s.full();
    return;
  }
  ordered_json j;
  j["file"] = a.file;
  j["kind"] = s.is_point_cloud ? "point_cloud" : "mesh";
  j["num_vertices"] = s.num_vertices;
  j["num_faces"] = s.num_faces;
  j["attributes"] = {{"normals", s.has_normals}, {"colors", s.has_colors}, {"texcoords", s.has_texcoords}};
  j["num_non_finite_vertices"] = s.num_non_finite_vertices;
  j["bbox"] = {{"min", vec_json(s.bbox_min)}, {"max", vec_json(s.bbox_max)},
               {"size", vec_json(s.bbox_max - s.bbox_min)}};
  j["max_extent"] = s.max_extent;
  if (s.units) {
    j["units"] = std::string(mesh::units_name(*s.units));
    j["units_source"] = s.units_detected ? "guessed" : "given";
    j["max_extent_mm"] = *s.max_extent_mm;
  } else {
    j["units"] = nullptr;
    j["units_source"] = nullptr;
    j["units_problem"] = s.units_problem;
    j["max_extent_mm"] = nullptr;
  }
  if (s.edge_lengths) {
    j["edge_length"] = {{"count", s.edge_lengths->count}, {"min", s.edge_lengths->min},
                        {"mean", s.edge_lengths->mean},   {"median", s.edge_lengths->median},
                        {"max", s.edge_lengths->max}};
  } else {
    j["edge_length"] = nullptr;
  }
  ordered_json loops = ordered_json::array();
  for (const auto& l : s.boundary_loops) loops.push_back({{"num_vertices", l.num_vertices}, {"length", l.length}});
  j["boundary"] = {{"num_edges", s.num_boundary_edges}, {"num_loops", s.boundary_loops.size()}, {"loops", loops}};
  j["components"] = {{"count", s.num_components}, {"face_counts", s.component_face_counts}};
  j["num_unreferenced_vertices"] = s.num_unreferenced_vertices;
  j["num_degenerate_faces"] = s.num_degenerate_faces;
  j["num_non_manifold_edges"] = s.num_non_manifold_edges;
  std::cout << j.dump(2) << "\n";
}

// ------------------------------------------------------------------------- landmarks / markups

/// What a landmark or markups file holds, ready to print.
struct PointsReport {
  std::string kind;                      // "markups" or "landmarks"
  std::optional<std::string> declared_units;
  std::string shown_units;               // units of the positions below ("mm", "m" or "file units")
  Markups content;
};

PointsReport read_points_file(const InspectArgs& a, FileKind kind, std::optional<mesh::Units> units) {
  PointsReport r;
  if (kind == FileKind::Markups) {
    r.kind = "markups";
    r.content = read_markups_warning(a.file).markups;  // LPS mm
    r.shown_units = "mm";
    try {
      r.declared_units = io::read_markups_file(a.file, {.convert_to_mm = false}).units;
    } catch (const IoError&) {
      r.declared_units = "mixed";
    }
    return r;
  }
  r.kind = "landmarks";
  LandmarkSet lm = read_landmarks_warning(a.file, {.require_known_names = false});
  r.declared_units = lm.declared_units;
  if (lm.declared_units || units) {
    lm = io::landmarks_to_mm(lm, units.value_or(mesh::Units::Millimetres));
    r.shown_units = "mm";
  } else {
    r.shown_units = "file units";
  }
  r.content.points = lm.points;
  return r;
}

void inspect_points(const InspectArgs& a, FileKind kind, std::optional<mesh::Units> units) {
  const PointsReport r = read_points_file(a, kind, units);
  const Markups& m = r.content;
  std::vector<std::string> unknown, missing;
  for (const auto& p : m.points)
    if (!landmark_index(p.name)) unknown.push_back(p.name);
  if (!m.points.empty())
    for (auto n : kLandmarkNames)
      if (!m.find_point(n)) missing.emplace_back(n);

  if (a.json) {
    ordered_json j;
    j["file"] = a.file;
    j["kind"] = r.kind;
    j["coordinate_system"] = "LPS";
    j["declared_units"] = r.declared_units ? ordered_json(*r.declared_units) : ordered_json(nullptr);
    j["units"] = r.shown_units;
    ordered_json pts = ordered_json::array();
    for (const auto& p : m.points)
      pts.push_back({{"name", p.name}, {"position", vec_json(p.position)}, {"known", landmark_index(p.name).has_value()}});
    j["points"] = pts;
    j["unknown_names"] = unknown;
    j["missing_landmarks"] = missing;
    ordered_json curves = ordered_json::array();
    for (const auto& c : m.curves)
      curves.push_back({{"name", c.name}, {"closed", c.closed}, {"num_points", c.points.rows()}, {"length", c.length()}});
    j["curves"] = curves;
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << "file: " << a.file << "\n";
  std::cout << "kind: " << r.kind << "\n";
  std::cout << "declared units: " << r.declared_units.value_or("none (plain file: pass --units to convert)") << "\n";
  std::cout << "positions: LPS, " << r.shown_units << "\n";
  std::cout << "points: " << m.points.size() << "\n";
  size_t width = 0;
  for (const auto& p : m.points) width = std::max(width, p.name.size());
  for (const auto& p : m.points) {
    std::cout << "  " << p.name << std::string(width - p.name.size(), ' ') << "  " << vec(p.position);
    if (!landmark_index(p.name)) std::cout << "  (not one of the 12 landmarks)";
    std::cout << "\n";
  }
  if (!missing.empty()) {
    std::cout << "missing landmarks:";
    for (const auto& n : missing) std::cout << " " << n;
    std::cout << "\n";
  }
  std::cout << "curves: " << m.curves.size() << "\n";
  for (const auto& c : m.curves)
    std::cout << "  " << c.name << "  " << (c.closed ? "closed" : "open") << ", " << c.points.rows()
              << " points, length " << num(c.length()) << " " << r.shown_units << "\n";
}

}  // namespace

void register_inspect(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<InspectArgs>();
  auto* sub = app.add_subcommand(
      "inspect", "Describe a mesh / point cloud (.ply .obj .stl .vtk .vtp) or a landmark / markups file (.mrk.json .json .csv .fcsv)");
  sub->add_option("file", args->file, "file to inspect")->required();
  sub->add_flag("--json", args->json, "print machine-readable JSON instead of text");
  sub->add_option("--units", args->units, "units of the file: auto (guess from the extent), mm or m")
      ->check(CLI::IsMember({"auto", "mm", "m"}));
  sub->callback([args] {
    const std::optional<mesh::Units> units = mesh::parse_units(args->units);
    const FileKind kind = kind_of(args->file);
    if (kind == FileKind::Mesh)
      inspect_mesh(*args, units);
    else
      inspect_points(*args, kind, units);
  });
}

}  // namespace breastfit::cli
