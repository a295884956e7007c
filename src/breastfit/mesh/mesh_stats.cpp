#include "breastfit/mesh/mesh_stats.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/adjacency.h"
#include "breastfit/mesh/boundary.h"
#include "breastfit/mesh/cleanup.h"
#include "breastfit/mesh/components.h"
#include "breastfit/mesh/triangle_indices.h"

namespace breastfit::mesh {
namespace {

std::string fmt(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

std::string fmt(const Vec3& v) {
  std::string s = "(";
  s += fmt(v.x());
  s += ", ";
  s += fmt(v.y());
  s += ", ";
  s += fmt(v.z());
  s += ')';
  return s;
}

EdgeLengthStats edge_length_stats(const Points& V, const Triangles& F) {
  const auto edges = unique_edges(F, static_cast<Index>(V.rows()));
  EdgeLengthStats s;
  s.count = static_cast<Index>(edges.size());
  if (edges.empty()) return s;
  std::vector<double> len;
  len.reserve(edges.size());
  double sum = 0.0;
  for (const auto& [a, b] : edges) {
    len.push_back((V.row(a) - V.row(b)).norm());
    sum += len.back();
  }
  s.mean = sum / static_cast<double>(len.size());
  const auto [mn, mx] = std::minmax_element(len.begin(), len.end());
  s.min = *mn;
  s.max = *mx;
  const size_t mid = len.size() / 2;
  std::nth_element(len.begin(), len.begin() + static_cast<std::ptrdiff_t>(mid), len.end());
  s.median = len[mid];
  if (len.size() % 2 == 0) {
    const double below = *std::max_element(len.begin(), len.begin() + static_cast<std::ptrdiff_t>(mid));
    s.median = 0.5 * (s.median + below);
  }
  return s;
}

}  // namespace

MeshStats mesh_stats(const TriangleMesh& mesh, std::optional<Units> units) {
  const Points& V = mesh.V;
  const Triangles& F = mesh.F;
  const Index nv = mesh.num_vertices();
  check_triangle_indices(F, nv);

  MeshStats s;
  s.num_vertices = nv;
  s.num_faces = mesh.num_faces();
  s.is_point_cloud = mesh.is_point_cloud();
  s.has_normals = mesh.has_normals();
  s.has_colors = mesh.has_colors();
  s.has_texcoords = mesh.has_texcoords();

  // Bounding box over finite vertices.
  Points finite(nv, 3);
  Index nf = 0;
  for (Index v = 0; v < nv; ++v)
    if (V.row(v).allFinite()) finite.row(nf++) = V.row(v);
  finite.conservativeResize(nf, 3);
  s.num_non_finite_vertices = nv - nf;
  if (nf > 0) {
    s.bbox_min = finite.colwise().minCoeff().transpose();
    s.bbox_max = finite.colwise().maxCoeff().transpose();
    s.max_extent = (s.bbox_max - s.bbox_min).maxCoeff();
  }

  if (!s.is_point_cloud) {
    s.edge_lengths = edge_length_stats(V, F);
    s.num_boundary_edges = static_cast<Index>(boundary_edges(F).size());
    for (const auto& loop : boundary_loops(F))
      s.boundary_loops.push_back({static_cast<Index>(loop.size()), loop_length(V, loop)});
    std::stable_sort(s.boundary_loops.begin(), s.boundary_loops.end(),
                     [](const BoundaryLoopStats& a, const BoundaryLoopStats& b) {
                       return a.length > b.length;
                     });
    const Components comps = connected_components(F, nv);
    s.num_components = comps.count();
    s.component_face_counts = comps.face_count;
    s.num_unreferenced_vertices = static_cast<Index>(
        std::count(comps.vertex_label.begin(), comps.vertex_label.end(), std::nullopt));
    s.num_degenerate_faces = count_degenerate_faces(V, F);
    s.num_non_manifold_edges = count_non_manifold_edges(F);
  }

  if (units) {
    s.units = units;
  } else {
    try {
      s.units = detect_units(finite);
      s.units_detected = true;
    } catch (const InvalidInput& e) {
      s.units_problem = e.what();
    }
  }
  if (s.units) s.max_extent_mm = s.max_extent * to_mm_factor(*s.units);
  return s;
}

std::string MeshStats::full() const {
  std::string o;
  auto line = [&](const std::string& k, const std::string& v) { o += k + ": " + v + "\n"; };
  line("kind", is_point_cloud ? "point cloud" : "triangle mesh");
  line("vertices", std::to_string(num_vertices));
  line("faces", std::to_string(num_faces));
  std::string attrs;
  if (has_normals) attrs += " normals";
  if (has_colors) attrs += " colors";
  if (has_texcoords) attrs += " texcoords";
  line("attributes", attrs.empty() ? "none" : attrs.substr(1));
  if (num_non_finite_vertices > 0) line("non-finite vertices", std::to_string(num_non_finite_vertices));
  line("bounding box min", fmt(bbox_min));
  line("bounding box max", fmt(bbox_max));
  line("bounding box size", fmt(Vec3(bbox_max - bbox_min)));
  if (units) {
    line("units", std::string(units_name(*units)) + (units_detected ? " (guessed from the extent)" : " (given)"));
    std::string extent = fmt(max_extent) + " " + std::string(units_name(*units));
    if (*units != Units::Millimetres) extent += " = " + fmt(*max_extent_mm) + " mm";
    line("max extent", extent);
  } else {
    line("units", "unknown: " + units_problem);
    line("max extent", fmt(max_extent));
  }
  if (edge_lengths) {
    line("edges", std::to_string(edge_lengths->count));
    line("edge length min/mean/median/max",
         fmt(edge_lengths->min) + " / " + fmt(edge_lengths->mean) + " / " +
             fmt(edge_lengths->median) + " / " + fmt(edge_lengths->max));
    line("boundary edges", std::to_string(num_boundary_edges));
    std::string loops = std::to_string(boundary_loops.size());
    const size_t shown = std::min<size_t>(boundary_loops.size(), 5);
    if (shown > 0) {
      loops += " (longest:";
      for (size_t i = 0; i < shown; ++i)
        loops += std::string(i ? ", " : " ") + fmt(boundary_loops[i].length) + " [" +
                 std::to_string(boundary_loops[i].num_vertices) + " vertices]";
      loops += boundary_loops.size() > shown ? ", ...)" : ")";
    }
    line("boundary loops", loops);
    std::string comps = std::to_string(num_components);
    const size_t cshown = std::min<size_t>(component_face_counts.size(), 5);
    if (cshown > 0) {
      comps += " (faces:";
      for (size_t i = 0; i < cshown; ++i)
        comps += std::string(i ? ", " : " ") + std::to_string(component_face_counts[i]);
      comps += component_face_counts.size() > cshown ? ", ...)" : ")";
    }
    line("components", comps);
    line("unreferenced vertices", std::to_string(num_unreferenced_vertices));
    line("degenerate faces", std::to_string(num_degenerate_faces));
    line("non-manifold edges", std::to_string(num_non_manifold_edges));
  }
  return o;
}

}  // namespace breastfit::mesh
