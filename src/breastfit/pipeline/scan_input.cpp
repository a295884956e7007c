#include "breastfit/pipeline/scan_input.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "breastfit/core/errors.h"
#include "breastfit/io/landmarks_io.h"
#include "breastfit/mesh/cleanup.h"
#include "breastfit/spatial/knn_index.h"
#include "breastfit/spatial/point_cloud_normals.h"

namespace breastfit::pipeline {
namespace {

// One small triangle per point, in its tangent plane (so point-to-plane closest points work).
TriangleMesh splat_point_cloud(const Points& P, const Points& N, double radius) {
  TriangleMesh m;
  m.V.resize(3 * P.rows(), 3);
  m.F.resize(P.rows(), 3);
  for (Index i = 0; i < P.rows(); ++i) {
    const Vec3 n = N.row(i).transpose().normalized();
    const Vec3 a = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
    const Vec3 b = n.cross(a);
    const Vec3 p = P.row(i).transpose();
    for (int k = 0; k < 3; ++k) {
      const double ang = 2.0 * M_PI * k / 3.0;
      m.V.row(3 * i + k) = (p + radius * (std::cos(ang) * a + std::sin(ang) * b)).transpose();
      m.F(i, k) = 3 * i + k;
    }
  }
  return m;
}

}  // namespace

PreparedScan prepare_scan(const TriangleMesh& scan, const std::string& name, std::optional<mesh::Units> requested) {
  return prepare_scan(TriangleMesh(scan), name, requested);
}

PreparedScan prepare_scan(TriangleMesh&& scan, const std::string& name, std::optional<mesh::Units> requested) {
  PreparedScan out;
  if (scan.num_vertices() == 0) throw InvalidInput(name + ": the scan has no vertices");
  if (!scan.V.allFinite()) throw InvalidInput(name + ": the scan has non-finite coordinates");
  try {
    out.units = mesh::resolve_units(requested, scan.V);
  } catch (const InvalidInput& e) {
    throw InvalidInput(name + ": " + e.what());
  }
  out.units_detected = !requested;
  out.extent = mesh::max_extent(scan.V);
  out.to_mm = mesh::to_mm_factor(out.units);
  const double extent_mm = out.extent * out.to_mm;
  if (extent_mm < 150.0 || extent_mm > 1500.0) {
    std::ostringstream s;
    s << name << ": the scan spans " << extent_mm << " mm in " << mesh::units_name(out.units)
      << ", not an upper torso (expected about 250-700 mm); wrong --units?";
    throw InvalidInput(s.str());
  }
  if (extent_mm < kTorsoExtentMm[0] || extent_mm > kTorsoExtentMm[1]) {
    std::ostringstream s;
    s << name << ": the scan spans " << std::lround(extent_mm) << " mm (in " << mesh::units_name(out.units)
      << "), " << (extent_mm < kTorsoExtentMm[0] ? "small" : "large")
      << " for an adult upper torso (about 250-700 mm): check --units and what was scanned";
    out.warnings.push_back(s.str());
  }
  const bool point_cloud = scan.is_point_cloud();
  const Index num_vertices = scan.num_vertices();
  out.mesh_mm = std::move(scan);  // the caller's scan is not needed any more: not copied (2 copies of V and F less)
  if (out.to_mm != 1.0) out.mesh_mm.V *= out.to_mm;  // x * 1.0 is x: the same bits without the pass
  out.mesh_mm.N.resize(0, 3);
  if (point_cloud) {
    if (num_vertices < 100) throw InvalidInput(name + ": a point cloud of fewer than 100 points");
    out.was_point_cloud = true;
    const Points N = spatial::point_cloud_normals(out.mesh_mm.V);
    // splat radius: median nearest-neighbour spacing
    spatial::KnnIndex knn(out.mesh_mm.V);
    std::vector<double> spacing;
    std::vector<Index> idx;
    std::vector<double> sq;
    for (Index i = 0; i < out.mesh_mm.V.rows(); i += std::max<Index>(1, out.mesh_mm.V.rows() / 2000)) {
      knn.knn(out.mesh_mm.V.row(i).transpose(), 2, idx, sq);
      if (sq.size() == 2) spacing.push_back(std::sqrt(sq[1]));
    }
    std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
    const double radius = std::max(0.5, 1.5 * spacing[spacing.size() / 2]);
    out.mesh_mm = splat_point_cloud(out.mesh_mm.V, N, radius);
    out.warnings.push_back(name + " is a point cloud: normals estimated, border rejection disabled");
  } else {
    const auto removed = mesh::remove_degenerate_faces(out.mesh_mm);
    if (removed > 0) out.warnings.push_back(name + ": " + std::to_string(removed) + " degenerate faces ignored");
    if (out.mesh_mm.num_faces() == 0) throw InvalidInput(name + ": every face of the scan is degenerate");
  }
  return out;
}

std::vector<std::pair<std::string, Vec3>> prepare_landmarks(const LandmarkSet& landmarks, mesh::Units scan_units) {
  const LandmarkSet mm = io::landmarks_to_mm(landmarks, scan_units);
  std::vector<std::pair<std::string, Vec3>> out;
  for (const auto& p : mm.points) out.emplace_back(p.name, p.position);
  return out;
}

}  // namespace breastfit::pipeline
