#include "breastfit/io/detail/polygon_triangulation.h"

#include <algorithm>
#include <cmath>

namespace breastfit::io::detail {
namespace {

using Corner = std::array<std::size_t, 3>;
using Vec2 = Eigen::Vector2d;

/// z of (b - a) x (c - b): positive when a, b, c turn counter-clockwise.
double turn(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 e = b - a;
  const Vec2 f = c - b;
  return e.x() * f.y() - e.y() * f.x();
}

/// Whether p lies in the counter-clockwise triangle (a, b, c), its edges included.
bool in_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return turn(a, b, p) >= 0 && turn(b, c, p) >= 0 && turn(c, a, p) >= 0;
}

void append_fan(const std::vector<std::size_t>& order, std::vector<Corner>& out) {
  for (std::size_t i = 1; i + 1 < order.size(); ++i) out.push_back({order[0], order[i], order[i + 1]});
}

/// Newell's normal of the polygon (its length is twice the projected area).
Vec3 newell_normal(const std::vector<Vec3>& p) {
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& a = p[i];
    const Vec3& b = p[(i + 1) % p.size()];
    n.x() += (a.y() - b.y()) * (a.z() + b.z());
    n.y() += (a.z() - b.z()) * (a.x() + b.x());
    n.z() += (a.x() - b.x()) * (a.y() + b.y());
  }
  return n;
}

/// The corners in the plane normal to `n`, counter-clockwise for a polygon winding around n.
std::vector<Vec2> project(const std::vector<Vec3>& p, const Vec3& n) {
  const Vec3 w = n.normalized();
  const Vec3 helper = std::abs(w.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = w.cross(helper).normalized();
  const Vec3 v = w.cross(u);  // u x v = w
  std::vector<Vec2> q;
  q.reserve(p.size());
  for (const Vec3& x : p) q.emplace_back(x.dot(u), x.dot(v));
  return q;
}

/// Cuts ears off the counter-clockwise polygon q (see triangulate_polygon).
void clip_ears(const std::vector<Vec2>& q, std::vector<Corner>& out) {
  std::vector<std::size_t> left(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) left[i] = i;
  while (left.size() > 3) {
    bool clipped = false;
    for (std::size_t k = 0; k < left.size() && !clipped; ++k) {
      const std::size_t a = left[(k + left.size() - 1) % left.size()];
      const std::size_t b = left[k];
      const std::size_t c = left[(k + 1) % left.size()];
      if (turn(q[a], q[b], q[c]) <= 0) continue;  // reflex or flat: not an ear
      bool empty = true;
      for (std::size_t r : left) {
        if (r == a || r == b || r == c || q[r] == q[a] || q[r] == q[b] || q[r] == q[c]) continue;
        if (in_triangle(q[r], q[a], q[b], q[c])) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      out.push_back({a, b, c});
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(k));
      clipped = true;
    }
    if (!clipped) break;
  }
  append_fan(left, out);
}

}  // namespace

void triangulate_polygon(const std::vector<Vec3>& corners, std::vector<Corner>& out) {
  out.clear();
  if (corners.size() == 3) {  // the common case, without allocating
    out.push_back({0, 1, 2});
    return;
  }
  std::vector<std::size_t> order(corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i) order[i] = i;
  const Vec3 n = newell_normal(corners);
  if (!(n.norm() > 0)) {  // degenerate (also NaN)
    append_fan(order, out);
    return;
  }
  const std::vector<Vec2> q = project(corners, n);
  // Rounding in the projection must not make a convex polygon with collinear corners concave:
  // a corner is reflex only when it turns clockwise by more than a tiny fraction of the size.
  double extent = 0;
  for (const Vec2& x : q) extent = std::max(extent, (x - q[0]).squaredNorm());
  const double tolerance = 1e-9 * extent;
  bool convex = true;
  for (std::size_t i = 0; i < q.size() && convex; ++i)
    convex = turn(q[i], q[(i + 1) % q.size()], q[(i + 2) % q.size()]) >= -tolerance;
  if (convex) {
    append_fan(order, out);
  } else {
    clip_ears(q, out);
  }
}

void PolygonTriangulator::append(const std::vector<double>& V, const Index* corners,
                                 std::size_t count, std::vector<Index>& tris) {
  if (count < 3) return;
  if (count == 3) {
    if (corners[0] != corners[1] && corners[1] != corners[2] && corners[0] != corners[2]) {
      tris.insert(tris.end(), corners, corners + 3);
    }
    return;
  }
  positions_.clear();
  for (std::size_t k = 0; k < count; ++k) {
    const auto at = 3 * static_cast<std::size_t>(corners[k]);
    positions_.emplace_back(V[at], V[at + 1], V[at + 2]);
  }
  triangulate_polygon(positions_, triangles_);
  for (const auto& c : triangles_) {
    const Index a = corners[c[0]], b = corners[c[1]], d = corners[c[2]];
    if (a == b || b == d || a == d) continue;
    tris.push_back(a);
    tris.push_back(b);
    tris.push_back(d);
  }
}

}  // namespace breastfit::io::detail
