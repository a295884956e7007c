#pragma once
/// \file Which vertices of a fitted model the scan covers, and the surface error over them.
///
/// A fitted model vertex v with closest scan point c (distance d) is *covered* when the scan
/// really has surface there to compare with:
///  - c is not on the scan's open border (beyond a cut, over a hole, past the scanned area the
///    closest point lies on the border) — only for meshes (a point cloud has no border);
///  - d ≤ max_distance_mm (a model part the scan does not have, e.g. the closed bottom of a
///    template inside a torso scan cut at the waist, finds the far body wall);
///  - the model's and the scan's normals agree within max_normal_angle_deg (the scan's normals
///    are first turned to face the model's way by a majority vote of the close vertices, so
///    inward-facing scan triangles work too): the inside of a scan's wall is not the model's skin;
///  - when d > direction_tolerance_mm, the offset v − c lies within max_normal_angle_deg of the
///    scan normal's line: the model point projects onto the scan, it does not lie beyond a cut
///    whose jagged border triangles are closest (the closest point of a vertex below a clipped
///    scan is its cut, reached sideways).
/// The surface error (the paper's MAE, SD, max) counts covered vertices only; the covered
/// fraction says how much of the model that is (docs/REPORT.md "Surface error").
#include <cstdint>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/metrics/distance_stats.h"

namespace breastfit::metrics {

struct CoverageOptions {
  bool skip_border = true;              ///< leave out vertices whose closest point is on the open border
  double max_distance_mm = 25.0;        ///< farther vertices are not covered, mm (> 0)
  double max_normal_angle_deg = 60.0;   ///< model/scan normal agreement and offset direction, degrees
  double direction_tolerance_mm = 2.0;  ///< below this distance the offset's direction is not checked, mm
};

/// Per-vertex distances and coverage of a fitted model against the scan.
struct SurfaceCoverage {
  /// |v − c| for every vertex within max_distance_mm of the scan; +∞ beyond (not covered: the
  /// search stops there)
  std::vector<double> distance_mm;
  std::vector<std::uint8_t> covered;  ///< 1 when the vertex is covered (see the file comment)
  Index covered_count = 0;
  CoverageOptions options;            ///< the rules applied
  /// covered_count / number of vertices (0 for no vertices)
  double fraction() const;
  /// The distances of the covered vertices, in vertex order.
  std::vector<double> covered_distances() const;
  /// distance_stats(covered_distances())
  DistanceStats stats() const;
};

/// Coverage of the mesh `fitted` (mm, consistently oriented triangles) by `scan`. `hints`
/// (optional, in/out): per vertex, the scan face to start its search from (< 0: the previous
/// vertex's), set to the face found — e.g. from the coverage of the same model with other offsets;
/// only the speed depends on them (a vector of another size is replaced).
SurfaceCoverage surface_coverage(const TriangleMesh& fitted, const fit::ScanTarget& scan,
                                 const CoverageOptions& options = {}, std::vector<Index>* hints = nullptr);

}  // namespace breastfit::metrics
