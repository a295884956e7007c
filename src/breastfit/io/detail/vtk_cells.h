#pragma once
/// \file Cells of VTK files (legacy .vtk and XML .vtp) turned into triangles, with the checks
/// both readers share (private to the io layer).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/io/detail/polygon_triangulation.h"
#include "breastfit/io/detail/slicer_space.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io::detail {

/// How a VTK cell makes triangles.
enum class VtkCellKind {
  Polygon,        ///< triangle (VTK type 5), quad (9), polygon (7): ear-clipped when concave
  TriangleStrip,  ///< triangle strip (6): alternating winding, as PLY tristrips
  Pixel,          ///< pixel (8): a quad whose corners are listed 0 1 3 2
  Other,          ///< vertices, lines, volume cells (tetra, hexahedron, ...): no triangles
};

/// The kind of the cell with VTK type id `type` (UNSTRUCTURED_GRID's CELL_TYPES).
VtkCellKind vtk_cell_kind(std::int64_t type);

/// Cells as VTK ≥ 5.1 and XML files store them: cell i holds
/// connectivity[offsets[i] .. offsets[i+1]); offsets starts with 0.
struct VtkCellArray {
  std::vector<std::int64_t> offsets{0};
  std::vector<std::int64_t> connectivity;
  std::size_t size() const { return offsets.size() - 1; }
};

/// Checks that `cells.offsets` starts at 0, never decreases and ends at the connectivity's size.
/// \throws IoError(name, "<section>: ...") otherwise
void check_vtk_cell_array(const VtkCellArray& cells, const std::string& name,
                          std::string_view section);

/// Collects the triangles of a file's cells, checking every point index.
class VtkTriangles {
 public:
  /// \param name    file name for messages
  /// \param points  the file's points (3 doubles each, all already read)
  VtkTriangles(const std::string& name, const std::vector<double>& points);

  /// Adds cell `cell` of `section` (for messages), of the given kind, with points
  /// `ids[0..count)`.
  /// \throws IoError(name, "<section> cell <cell> references point <p> but the file has <n>
  ///         points") for an index out of range
  void add(VtkCellKind kind, const std::int64_t* ids, std::size_t count, std::string_view section,
           std::size_t cell);

  /// Adds every cell of `cells` with one kind.
  void add_all(VtkCellKind kind, const VtkCellArray& cells, std::string_view section);

  /// The triangles so far, 3 indices each.
  const std::vector<Index>& triangles() const { return tris_; }

 private:
  const std::string& name_;
  const std::vector<double>& points_;
  std::vector<Index> ids_;
  std::vector<Index> tris_;
  PolygonTriangulator triangulator_;
};

/// Point attributes a VTK reader kept, as flat arrays (3 normals, 3 colours, 2 texture
/// coordinates per point; empty when the file has none).
struct VtkPointData {
  std::vector<double> normals, uv;
  std::vector<std::uint8_t> colors;
};

/// The mesh of `points` (3 doubles each) and `triangles`, with each attribute of `data` that is
/// complete and finite, converted to LPS when `space` is Ras.
TriangleMesh vtk_mesh(const std::vector<double>& points, const std::vector<Index>& triangles,
                      const VtkPointData& data, SlicerSpace space);

}  // namespace breastfit::io::detail
