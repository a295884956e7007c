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
  Index face = 0;      ///< scan triangle holding `point`
  bool on_boundary = false;  ///< the closest feature lies on the scan's open border
};

class ScanTarget {
 public:
  /// \param scan_mm the scan in millimetres (a triangle mesh; point clouds are meshed by the caller).
  /// \param threads threads of the index build, as FitOptions::threads (0: all free cores); the
  ///        target is the same bits for any number.
  /// \throws InvalidInput when the scan has no triangles.
  explicit ScanTarget(const TriangleMesh& scan_mm, int num_samples = 1500, int threads = 1);
  ~ScanTarget();
  ScanTarget(ScanTarget&&) noexcept;

  /// Closest point within max_dist, or nullopt. `hint_face` (optional, in/out): a face to start
  /// the search from (e.g. this query's face at the previous iteration; < 0 = none), updated to
  /// the face found. The result does not depend on the hint, only the speed.
  std::optional<ScanMatch> match(const Vec3& q, double max_dist, Index* hint_face = nullptr) const;
  /// Exact closest point (no radius). `hint_face` (optional, in/out) as for match(): only the
  /// speed depends on it (e.g. the previous query's face for a run of nearby queries).
  ScanMatch closest(const Vec3& q, Index* hint_face = nullptr) const;

  /// Multiplies every returned normal (−1 when the scan's triangles face inwards).
  void set_normal_sign(double sign) { normal_sign_ = sign; }
  double normal_sign() const { return normal_sign_; }

  /// The scan as given (the index's copy: the target keeps no second one).
  const TriangleMesh& mesh() const;
  /// The scan's closest-point index, for other queries on the scan than the fit's (e.g. its
  /// vertices around a landmark) without a second index.
  const spatial::ClosestPointIndex& index() const { return *index_; }
  /// The scan's area-weighted unit vertex normals as given (mesh::vertex_normals(mesh()), not
  /// multiplied by normal_sign()): the index's, computed once with it.
  const Points& vertex_normals() const;
  /// Deterministic area-uniform samples (points and unit normals, oriented by normal_sign())
  /// of the scan, for the reverse term.
  const Points& sample_points() const { return samples_; }
  Points sample_normals() const;
  /// Per scan vertex: 1 on the skin, else 0 (fit/skin_around.h skin_vertices(mesh())): computed on
  /// first use and kept, so that the warm re-fits of a workstation session on the same target
  /// label the scan's pieces once. Thread-safe.
  const std::vector<char>& skin() const;

 private:
  struct Skin;  // the labels and their once-flag
  std::unique_ptr<spatial::ClosestPointIndex> index_;  // owns the scan's copy
  std::unique_ptr<Skin> skin_;
  Points samples_;
  Points sample_normals_;
  double normal_sign_ = 1.0;
};

}  // namespace breastfit::fit
