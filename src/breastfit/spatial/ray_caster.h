#pragma once
/// \file Ray casting against a triangle mesh (first hit and occlusion), over the same BVH as the
/// closest-point index; used to simulate what a scanner sees.
#include <limits>
#include <memory>
#include <optional>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::spatial {

/// First intersection of a ray with the mesh.
struct RayHit {
  Index face = 0;             ///< triangle hit
  double t = 0.0;             ///< ray parameter: point = origin + t·dir (mm when dir is unit)
  Vec3 bary = Vec3::Zero();   ///< barycentrics of the hit in `face` (>= 0, sum 1)
  Vec3 point = Vec3::Zero();  ///< the hit point, bary-weighted corners of `face`
};

/// Möller–Trumbore intersection of the ray origin + t·dir, t in [t_min, t_max], with triangle
/// (a, b, c), both sides. Barycentric tests carry a 1e-12 tolerance (then clamped), so a ray
/// through a shared edge hits at least one of the two triangles. Degenerate (zero-area)
/// triangles are never hit. `face` of the result is 0.
std::optional<RayHit> intersect_ray_triangle(const Vec3& origin, const Vec3& dir, const Vec3& a,
                                             const Vec3& b, const Vec3& c, double t_min,
                                             double t_max);

/// Built once over a triangle mesh (BVH); queries are const and thread-safe.
///
/// Example:
/// \code
///   const spatial::RayCaster caster(scan);
///   if (auto hit = caster.intersect(camera, (p - camera).normalized())) { use(hit->face); }
///   bool hidden = caster.occluded(p, camera);
/// \endcode
class RayCaster {
 public:
  /// \throws InvalidInput when the mesh has no triangles, non-finite vertices or bad indices.
  explicit RayCaster(const TriangleMesh& mesh);
  ~RayCaster();
  RayCaster(RayCaster&&) noexcept;
  RayCaster& operator=(RayCaster&&) noexcept;

  /// Nearest hit with t in [0, t_max] (both triangle sides); ties in t go to the lowest face.
  /// \param[in] dir any non-zero direction; t is measured in units of |dir|.
  /// \throws InvalidInput when origin/dir are not finite or dir is zero, or t_max is NaN.
  std::optional<RayHit> intersect(const Vec3& origin, const Vec3& dir,
                                  double t_max = std::numeric_limits<double>::infinity()) const;

  /// True when a triangle crosses the segment origin→target strictly between `eps` (mm) from
  /// either end (so a surface point does not occlude itself). Any-hit: stops at the first one.
  /// \throws InvalidInput when the points are not finite or eps < 0.
  bool occluded(const Vec3& origin, const Vec3& target, double eps = 1e-6) const;

  const TriangleMesh& mesh() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace breastfit::spatial
