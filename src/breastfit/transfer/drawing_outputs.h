#pragma once
/// \file Files a clinical team can open for the transferred drawings: polylines as PLY
/// (vertices + `edge` element: MeshLab, 3D Slicer, CloudCompare) and OBJ (`l` lines), and the
/// scan with the drawings painted into its vertex colours.
///
/// Every writer takes positions in mm and a factor `from_mm` (1 for mm files, 0.001 for metres)
/// so the files are in the scan's own units and frame.
#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "breastfit/mesh/drawing_palette.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/transfer/drawing_transfer.h"

namespace breastfit::transfer {

using Rgb = std::array<std::uint8_t, 3>;

/// The colour of a drawing for PLY and painting: mesh::drawing_colour (the one palette of the
/// figures, `render` and the workstation), by kind; other drawings by `index` in `curves`.
Rgb drawing_color(const std::string& name, size_t index = 0);

/// Writes the curves as an ASCII PLY: `element vertex` (x y z as double, red green blue per
/// curve), then `element edge` (vertex1 vertex2), a closed curve with its closing edge; one
/// `comment curve <name> <first vertex> <count> <open|closed>` line per curve.
/// \param[in] from_mm  multiplies every coordinate (> 0)
/// \throws InvalidInput for from_mm <= 0; IoError(path, problem) when the file cannot be written
void write_drawings_ply(const std::filesystem::path& path, const std::vector<TransferredCurve>& curves, double from_mm = 1.0);

/// Writes the curves as an OBJ: `v` lines, then per curve `o <name>` and one `l` line through its
/// vertices (a closed curve repeats its first index at the end).
/// \throws InvalidInput for from_mm <= 0; IoError(path, problem) when the file cannot be written
void write_drawings_obj(const std::filesystem::path& path, const std::vector<TransferredCurve>& curves, double from_mm = 1.0);

struct PaintOptions {
  double width_mm = 3.0;        ///< painted band width (vertices within width/2 of a curve), mm (> 0)
  Rgb skin{224, 182, 160};      ///< colour of every other vertex
};

/// The colours paint_drawings gives the scan's vertices (#V by 3), without copying the scan.
/// \throws InvalidInput for a non-positive width
Colors paint_colors(const TriangleMesh& scan_mm, const std::vector<TransferredCurve>& curves,
                    const PaintOptions& options = {});

/// The scan (mm) with vertex colours: the drawing colour within width/2 of a curve, skin elsewhere;
/// where bands overlap the later curve of `curves` is on top. Vertices and faces are unchanged.
/// \throws InvalidInput for a non-positive width
TriangleMesh paint_drawings(const TriangleMesh& scan_mm, const std::vector<TransferredCurve>& curves,
                            const PaintOptions& options = {});

/// paint_drawings, scaled by from_mm, written as a binary PLY with colours.
/// \throws InvalidInput / IoError as paint_drawings and io::write_mesh
void write_scan_painted(const std::filesystem::path& path, const TriangleMesh& scan_mm,
                        const std::vector<TransferredCurve>& curves, double from_mm = 1.0,
                        const PaintOptions& options = {});

}  // namespace breastfit::transfer
