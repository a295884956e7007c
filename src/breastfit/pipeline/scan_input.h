#pragma once
/// \file A scan as the user gave it, made ready for registration: units resolved and converted to
/// millimetres, checked to be an upper torso, point clouds turned into oriented splats.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "breastfit/mesh/landmarks.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/mesh/units.h"

namespace breastfit::pipeline {

struct PreparedScan {
  TriangleMesh mesh_mm;          ///< triangles in mm (splats for a point cloud)
  mesh::Units units = mesh::Units::Millimetres;  ///< the file's units
  double to_mm = 1.0;            ///< file units → mm
  bool was_point_cloud = false;
  bool units_detected = false;   ///< the units came from the scan's extent (not requested)
  double extent = 0;             ///< largest bounding-box extent, file units
  std::vector<std::string> warnings;
};

/// The extent (mm, largest side of the bounding box) of a plausible adult upper-torso scan: a
/// scan outside it (but within 150–1500 mm) is kept with a warning — a 0.155 m bunny taken as
/// 155 mm, a full-body scan.
inline constexpr std::array<double, 2> kTorsoExtentMm{250.0, 1000.0};

/// Converts `scan` (file units) to mm and validates it.
/// \param name       used in error messages (the file name)
/// \param requested  forced units, or nullopt to detect them from the extent
/// \throws InvalidInput for an empty scan, non-finite coordinates, or an extent that is not an
///         upper torso (150–1500 mm after conversion), each naming the file; warns outside
///         kTorsoExtentMm.
PreparedScan prepare_scan(const TriangleMesh& scan, const std::string& name, std::optional<mesh::Units> requested);
/// The same, taking over `scan`'s arrays instead of copying them (`register`: the scan as read is
/// not needed after its preparation).
PreparedScan prepare_scan(TriangleMesh&& scan, const std::string& name, std::optional<mesh::Units> requested);

/// Landmarks converted to mm (declared units, else the scan's), checked for NaN.
std::vector<std::pair<std::string, Vec3>> prepare_landmarks(const LandmarkSet& landmarks, mesh::Units scan_units);

}  // namespace breastfit::pipeline
