#include "breastfit/io/detail/vtk_cells.h"

#include <algorithm>
#include <cmath>

#include "breastfit/core/errors.h"
#include "breastfit/io/detail/mesh_arrays.h"
#include "breastfit/mesh/index_triangulation.h"

namespace breastfit::io::detail {

VtkCellKind vtk_cell_kind(std::int64_t type) {
  switch (type) {
    case 5:  // VTK_TRIANGLE
    case 7:  // VTK_POLYGON
    case 9:  // VTK_QUAD
      return VtkCellKind::Polygon;
    case 6:  // VTK_TRIANGLE_STRIP
      return VtkCellKind::TriangleStrip;
    case 8:  // VTK_PIXEL
      return VtkCellKind::Pixel;
    default:
      return VtkCellKind::Other;
  }
}

void check_vtk_cell_array(const VtkCellArray& cells, const std::string& name,
                          std::string_view section) {
  const std::string where(section);
  if (cells.offsets.empty() || cells.offsets.front() != 0) {
    throw IoError(name, where + ": the cell offsets do not start at 0");
  }
  for (std::size_t i = 0; i + 1 < cells.offsets.size(); ++i) {
    if (cells.offsets[i + 1] < cells.offsets[i]) {
      throw IoError(name, where + ": the cell offsets decrease at cell " + std::to_string(i));
    }
  }
  if (static_cast<std::uint64_t>(cells.offsets.back()) != cells.connectivity.size()) {
    throw IoError(name, where + ": the cell offsets end at " + std::to_string(cells.offsets.back()) +
                            " but the connectivity holds " +
                            std::to_string(cells.connectivity.size()) + " point indices");
  }
}

VtkTriangles::VtkTriangles(const std::string& name, const std::vector<double>& points)
    : name_(name), points_(points) {}

void VtkTriangles::add(VtkCellKind kind, const std::int64_t* ids, std::size_t count,
                       std::string_view section, std::size_t cell) {
  const auto num_points = static_cast<std::int64_t>(points_.size() / 3);
  ids_.clear();
  for (std::size_t k = 0; k < count; ++k) {
    if (ids[k] < 0 || ids[k] >= num_points) {
      throw IoError(name_, std::string(section) + " cell " + std::to_string(cell) +
                               " references point " + std::to_string(ids[k]) +
                               " but the file has " + std::to_string(num_points) + " points");
    }
    ids_.push_back(static_cast<Index>(ids[k]));
  }
  switch (kind) {
    case VtkCellKind::Polygon:
      triangulator_.append(points_, ids_.data(), ids_.size(), tris_);
      break;
    case VtkCellKind::TriangleStrip:
      mesh::append_strip_triangles(ids_.data(), ids_.size(), tris_);
      break;
    case VtkCellKind::Pixel:
      if (ids_.size() == 4) {
        std::swap(ids_[2], ids_[3]);
        triangulator_.append(points_, ids_.data(), ids_.size(), tris_);
      }
      break;
    case VtkCellKind::Other:
      break;
  }
}

void VtkTriangles::add_all(VtkCellKind kind, const VtkCellArray& cells, std::string_view section) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const auto begin = static_cast<std::size_t>(cells.offsets[i]);
    const auto end = static_cast<std::size_t>(cells.offsets[i + 1]);
    add(kind, cells.connectivity.data() + begin, end - begin, section, i);
  }
}

TriangleMesh vtk_mesh(const std::vector<double>& points, const std::vector<Index>& triangles,
                      const VtkPointData& data, SlicerSpace space) {
  const auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  TriangleMesh mesh;
  mesh.V = to_points(points);
  mesh.F = to_triangles(triangles);
  if (data.normals.size() == points.size() && finite(data.normals)) mesh.N = to_points(data.normals);
  if (data.colors.size() == points.size()) mesh.C = to_colors(data.colors);
  if (data.uv.size() == 2 * (points.size() / 3) && finite(data.uv)) {
    mesh.UV = to_texcoords(data.uv);
    mesh.FUV = mesh.F;
  }
  if (space == SlicerSpace::Ras) ras_to_lps(mesh);
  return mesh;
}

}  // namespace breastfit::io::detail
