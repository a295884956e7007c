#pragma once
/// \file The scan as a registration target: exact closest points on its triangles with normals
/// and open-border flags, consistently oriented normals, and samples for the reverse term.
#include <memory>
#include <optional>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::spatial {
class ClosestPointIndex;
}

namespace breastfit::fit {

struct ScanMatch {
  Vec3 point;          ///< closest point on the scan, mm
  Vec3 normal;         ///< unit surface normal there (oriented by normal_sign())
  double sq_dist = 0;  ///< squared distance query→point, mm²
  bool on_boundary = false;  ///< the closest feature lies on the scan's open border
};

class ScanTarget {
 public:
  /// \param scan_mm the scan in millimetres (a triangle mesh; point clouds are meshed by the caller).
  /// \throws InvalidInput when the scan has no triangles.
  explicit ScanTarget(const TriangleMesh& scan_mm, int num_samples = 1500);
  ~ScanTarget();
  ScanTarget(ScanTarget&&) noexcept;

  /// Closest point within max_dist, or nullopt.
  std::optional<ScanMatch> match(const Vec3& q, double max_dist) const;
  /// Exact closest point (no radius).
  ScanMatch closest(const Vec3& q) const;

  /// Multiplies every returned normal (−1 when the scan's triangles face inwards).
  void set_normal_sign(double sign) { normal_sign_ = sign; }
  double normal_sign() const { return normal_sign_; }

  const TriangleMesh& mesh() const { return mesh_; }
  /// Deterministic area-uniform samples (points and unit normals, oriented by normal_sign())
  /// of the scan, away from its open border, for the reverse term.
  const Points& sample_points() const { return samples_; }
  Points sample_normals() const;
  /// Vertex area-weighted normals of the scan (unoriented, as the triangles say).
  const Points& vertex_normals() const { return vertex_normals_; }

 private:
  TriangleMesh mesh_;
  std::unique_ptr<spatial::ClosestPointIndex> index_;
  Points vertex_normals_;
  Points samples_;
  Points sample_normals_;
  double normal_sign_ = 1.0;
};

}  // namespace breastfit::fit
