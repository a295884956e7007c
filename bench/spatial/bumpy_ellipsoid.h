#pragma once
// The benchmarks' test surface: a bumpy ellipsoid from a subdivided icosahedron.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::bench {

/// Icosphere subdivided `levels` times (20·4^levels triangles), then mapped onto an ellipsoid
/// with semi-axes (150, 100, 200) mm and a few percent of smooth bumps.
inline TriangleMesh bumpy_ellipsoid(int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                         {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                         {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v) p.normalize();
  std::vector<std::array<Index, 3>> f = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::unordered_map<std::uint64_t, Index> mid;
    mid.reserve(f.size() * 2);
    auto midpoint = [&](Index a, Index b) {
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
                                static_cast<std::uint32_t>(std::max(a, b));
      const auto [it, inserted] = mid.emplace(key, static_cast<Index>(v.size()));
      if (inserted) v.push_back((v[a] + v[b]).normalized());
      return it->second;
    };
    std::vector<std::array<Index, 3>> g;
    g.reserve(4 * f.size());
    for (const auto& tri : f) {
      const Index a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]),
                  c = midpoint(tri[2], tri[0]);
      g.push_back({tri[0], a, c});
      g.push_back({tri[1], b, a});
      g.push_back({tri[2], c, b});
      g.push_back({a, b, c});
    }
    f.swap(g);
  }
  TriangleMesh m;
  m.V.resize(static_cast<Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3& p = v[i];
    const double bump = 1.0 + 0.03 * std::sin(7 * p.x()) * std::cos(5 * p.y()) +
                        0.02 * std::sin(11 * p.z() + 3 * p.x());
    m.V.row(static_cast<Index>(i)) = Vec3(150 * p.x(), 100 * p.y(), 200 * p.z()) * bump;
  }
  m.F.resize(static_cast<Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) {
    for (int k = 0; k < 3; ++k) m.F(static_cast<Index>(i), k) = f[i][k];
  }
  return m;
}

}  // namespace breastfit::bench
