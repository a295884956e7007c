#pragma once
/// \file Carrying points and curves between two fits of the same template (e.g. a patient's
/// standing and supine scans) through template correspondence: closest point on fitted A
/// (triangle + barycentrics) → the same surface point on fitted B → optionally projected onto
/// scan B (docs/TRANSFER.md).
#include <memory>
#include <string>
#include <vector>

#include "breastfit/fit/scan_target.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/mesh/surface_point.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/spatial/closest_point_index.h"
#include "breastfit/transfer/drawing_transfer.h"

namespace breastfit::transfer {

/// Surface correspondence between two posings of one triangle mesh.
class SurfaceMap {
 public:
  /// \param from_mm, to_mm  the same template posed twice (same F, same #V), mm
  /// \throws InvalidInput when the topologies differ or a mesh has no triangles
  SurfaceMap(const TriangleMesh& from_mm, const TriangleMesh& to_mm);
  ~SurfaceMap();

  struct Mapped {
    SurfacePoint surface;          ///< the template surface point (face, barycentrics)
    Vec3 on_from = Vec3::Zero();   ///< its position on `from`, mm
    Vec3 on_to = Vec3::Zero();     ///< its position on `to`, mm
    double distance_from_mm = 0;   ///< |q − on_from|: how far the input was from fitted A
  };
  /// Maps one position (mm, frame of `from`).
  Mapped map(const Vec3& q) const;

  const TriangleMesh& to() const { return to_; }

 private:
  spatial::ClosestPointIndex from_index_;
  TriangleMesh to_;
};

struct MapOptions {
  /// Confidence levels: "high" when the input is within this of fitted A (and, with a scan B,
  /// the output is supported by it), mm.
  double high_confidence_mm = 3.0;
  /// "medium" up to this distance (and supported); "low" beyond or when unsupported by scan B, mm.
  double medium_confidence_mm = 10.0;
  /// Projection onto scan B (threshold, border and normal tests); only the single-point
  /// projection is used: control points are mapped one to one, never resampled or smoothed.
  TransferOptions projection;
  /// \throws InvalidInput naming the field
  void validate() const;
};

/// How much to trust one mapped control point.
struct MappedPoint {
  std::string markup;             ///< "points" for point lists, else the curve's name
  std::string label;              ///< point name (point lists) or index along the curve
  Vec3 input = Vec3::Zero();      ///< mm, frame A
  Vec3 output = Vec3::Zero();     ///< mm, frame B
  double distance_to_fit_a_mm = 0;  ///< input → fitted A surface; large = drawn off the fitted surface
  bool projected = false;         ///< a scan B was given
  bool supported_by_scan_b = false; ///< the output is on scan B (false without a scan)
  double scan_b_offset_mm = 0;    ///< fitted B → scan B distance at the output (0 when not projected)
  std::string confidence;         ///< "high", "medium" or "low"
};

struct MapResult {
  Markups markups;                ///< the mapped points and curves, mm, frame B, same names/order
  std::vector<MappedPoint> points;  ///< one per control point, in file order (points, then curves)
  int count(const std::string& confidence) const;
};

/// Maps every point and curve control point of `input` (mm, frame of fit A) to fit B.
/// \param scan_b  optional scan B (mm); when given, outputs are projected onto it where supported
/// \throws InvalidInput for invalid options or mismatched fits
MapResult map_markups(const Markups& input, const TriangleMesh& fit_a_mm, const TriangleMesh& fit_b_mm,
                      const fit::ScanTarget* scan_b, const MapOptions& options = {});

}  // namespace breastfit::transfer
