#include "breastfit/spatial/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "breastfit/core/errors.h"
#include "breastfit/spatial/detail/bvh.h"
#include "breastfit/spatial/detail/triangle_tables.h"

namespace breastfit::spatial {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kBaryTolerance = 1e-12;

/// Möller–Trumbore on raw coordinates; writes t, u, v (barycentrics of b and c) on a hit.
inline bool ray_triangle(const double* o, const double* d, const double* a, const double* b,
                         const double* c, double t_min, double t_max, double& t, double& u,
                         double& v) {
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double p[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2],
                       d[0] * e2[1] - d[1] * e2[0]};
  const double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
  if (det == 0.0 || !std::isfinite(det)) return false;
  const double inv = 1.0 / det;
  const double s[3] = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
  u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
  if (!(u >= -kBaryTolerance && u <= 1.0 + kBaryTolerance)) return false;
  const double qv[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2],
                        s[0] * e1[1] - s[1] * e1[0]};
  v = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) * inv;
  if (!(v >= -kBaryTolerance && u + v <= 1.0 + kBaryTolerance)) return false;
  t = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) * inv;
  if (!(t >= t_min && t <= t_max)) return false;
  // Clamp the tolerance away: barycentrics in [0, 1], summing to 1.
  u = std::clamp(u, 0.0, 1.0);
  v = std::clamp(v, 0.0, 1.0);
  if (u + v > 1.0) {
    const double sum = u + v;
    u /= sum;
    v /= sum;
  }
  return true;
}

/// Entry distance of the ray into a node's box within [t_min, t_max], or false. Slightly
/// conservative (the interval is widened by 1e-12 relative) so rounding never loses a hit.
inline bool ray_box(const detail::BvhNode& n, const double* o, const double* inv_d,
                    double t_min, double t_max, double& t_enter) {
  double t0 = t_min, t1 = t_max;
  for (int k = 0; k < 3; ++k) {
    const double lo = n.lo[k], hi = n.hi[k];
    if (std::isinf(inv_d[k])) {  // ray parallel to this slab
      if (o[k] < lo || o[k] > hi) return false;
      continue;
    }
    double a = (lo - o[k]) * inv_d[k], b = (hi - o[k]) * inv_d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a - 1e-12 * std::abs(a));
    t1 = std::min(t1, b + 1e-12 * std::abs(b));
  }
  t_enter = t0;
  return t0 <= t1;
}

}  // namespace

std::optional<RayHit> intersect_ray_triangle(const Vec3& origin, const Vec3& dir, const Vec3& a,
                                             const Vec3& b, const Vec3& c, double t_min,
                                             double t_max) {
  double t, u, v;
  if (!ray_triangle(origin.data(), dir.data(), a.data(), b.data(), c.data(), t_min, t_max, t, u,
                    v)) {
    return std::nullopt;
  }
  RayHit hit;
  hit.t = t;
  hit.bary = Vec3(1.0 - u - v, u, v);
  hit.point = hit.bary[0] * a + hit.bary[1] * b + hit.bary[2] * c;
  return hit;
}

struct RayCaster::Impl {
  TriangleMesh mesh;
  detail::Bvh bvh;

  explicit Impl(const TriangleMesh& m) : mesh(m) {
    detail::validate_triangle_mesh(mesh, "RayCaster");
    detail::BvhBuildOptions options;
    options.method = detail::BvhBuildMethod::Sah;  // rays profit more from SAH trees
    bvh = detail::Bvh::build(detail::triangle_boxes(mesh), options);
  }

  const double* vertex(Index f, int k) const {
    return mesh.V.data() + 3 * static_cast<std::ptrdiff_t>(mesh.F(f, k));
  }

  /// Closest hit in [t_min, t_max] (any_hit: the first one found). Returns the face or -1.
  Index trace(const double* o, const double* d, double t_min, double& t_max, double& u,
              double& v, bool any_hit) const {
    const double inv_d[3] = {1.0 / d[0], 1.0 / d[1], 1.0 / d[2]};
    const detail::BvhNode* nodes = bvh.nodes.data();
    double t_enter;
    if (!ray_box(nodes[0], o, inv_d, t_min, t_max, t_enter)) return -1;
    struct Entry {
      std::int32_t node;
      double t;
    };
    Entry stack[detail::kBvhMaxStack];
    int sp = 0;
    stack[sp++] = {0, t_enter};
    Index best = -1;
    while (sp > 0) {
      const Entry e = stack[--sp];
      if (e.t > t_max) continue;
      const detail::BvhNode& n = nodes[e.node];
      if (n.is_leaf()) {
        for (std::int32_t s = n.first; s < n.first + n.count; ++s) {
          const Index f = bvh.prims[s];
          double t, uu, vv;
          if (!ray_triangle(o, d, vertex(f, 0), vertex(f, 1), vertex(f, 2), t_min, t_max, t, uu,
                            vv)) {
            continue;
          }
          if (t < t_max || best < 0 || f < best) {
            t_max = t;
            u = uu;
            v = vv;
            best = f;
            if (any_hit) return best;
          }
        }
        continue;
      }
      double ta = 0.0, tb = 0.0;
      const bool ha = ray_box(nodes[n.first], o, inv_d, t_min, t_max, ta);
      const bool hb = ray_box(nodes[n.first + 1], o, inv_d, t_min, t_max, tb);
      if (ha && hb) {  // push the farther first so the nearer is popped first
        if (ta <= tb) {
          stack[sp++] = {n.first + 1, tb};
          stack[sp++] = {n.first, ta};
        } else {
          stack[sp++] = {n.first, ta};
          stack[sp++] = {n.first + 1, tb};
        }
      } else if (ha) {
        stack[sp++] = {n.first, ta};
      } else if (hb) {
        stack[sp++] = {n.first + 1, tb};
      }
    }
    return best;
  }
};

RayCaster::RayCaster(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {}
RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

std::optional<RayHit> RayCaster::intersect(const Vec3& origin, const Vec3& dir,
                                           double t_max) const {
  if (!origin.allFinite() || !dir.allFinite() || dir.squaredNorm() == 0.0) {
    throw InvalidInput("RayCaster::intersect: origin and dir must be finite, dir non-zero");
  }
  if (std::isnan(t_max)) throw InvalidInput("RayCaster::intersect: t_max is NaN");
  double t = t_max, u = 0.0, v = 0.0;
  const Index f = impl_->trace(origin.data(), dir.data(), 0.0, t, u, v, false);
  if (f < 0) return std::nullopt;
  RayHit hit;
  hit.face = f;
  hit.t = t;
  hit.bary = Vec3(1.0 - u - v, u, v);
  for (int k = 0; k < 3; ++k) {
    hit.point[k] = hit.bary[0] * impl_->vertex(f, 0)[k] + hit.bary[1] * impl_->vertex(f, 1)[k] +
                   hit.bary[2] * impl_->vertex(f, 2)[k];
  }
  return hit;
}

bool RayCaster::occluded(const Vec3& origin, const Vec3& target, double eps) const {
  if (!origin.allFinite() || !target.allFinite()) {
    throw InvalidInput("RayCaster::occluded: points must be finite");
  }
  if (!(eps >= 0.0)) {
    throw InvalidInput("RayCaster::occluded: eps must be >= 0, got " + std::to_string(eps));
  }
  const Vec3 d = target - origin;
  const double len = d.norm();
  if (len <= 2.0 * eps) return false;
  const Vec3 dir = d / len;
  double t = len - eps, u = 0.0, v = 0.0;
  return impl_->trace(origin.data(), dir.data(), eps, t, u, v, true) >= 0;
}

const TriangleMesh& RayCaster::mesh() const { return impl_->mesh; }

}  // namespace breastfit::spatial
