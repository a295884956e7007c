#pragma once
// Synthetic meshes for the spatial tests (closest point, ray casting): random triangle soups,
// an icosphere, a noisy open sheet with holes. Fixed seeds; header-only, test-only.
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "breastfit/core/rng.h"
#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::test::spatial_meshes {

inline TriangleMesh make_mesh(const std::vector<Vec3>& verts,
                              const std::vector<std::array<Index, 3>>& faces) {
  TriangleMesh m;
  m.V.resize(static_cast<Index>(verts.size()), 3);
  for (std::size_t i = 0; i < verts.size(); ++i) m.V.row(static_cast<Index>(i)) = verts[i];
  m.F.resize(static_cast<Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (int k = 0; k < 3; ++k) m.F(static_cast<Index>(i), k) = faces[i][k];
  }
  return m;
}

/// n random triangles with corners uniform in a cube of side `size`, edge lengths up to `edge`.
inline TriangleMesh random_soup(int n, double size, double edge, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Vec3> v;
  std::vector<std::array<Index, 3>> f;
  for (int i = 0; i < n; ++i) {
    const Vec3 c(rng.uniform(0, size), rng.uniform(0, size), rng.uniform(0, size));
    for (int k = 0; k < 3; ++k) {
      v.push_back(c + edge * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)));
    }
    f.push_back({3 * i, 3 * i + 1, 3 * i + 2});
  }
  return make_mesh(v, f);
}

/// Icosphere of radius r centred at c: 20·4^levels triangles, closed and manifold.
inline TriangleMesh icosphere(int levels, double r, const Vec3& c = Vec3::Zero()) {
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
    std::map<std::pair<Index, Index>, Index> mid;
    auto midpoint = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      const auto id = static_cast<Index>(v.size() - 1);
      mid.emplace(key, id);
      return id;
    };
    std::vector<std::array<Index, 3>> g;
    g.reserve(4 * f.size());
    for (const auto& tri : f) {
      const Index a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]),
                  d = midpoint(tri[2], tri[0]);
      g.push_back({tri[0], a, d});
      g.push_back({tri[1], b, a});
      g.push_back({tri[2], d, b});
      g.push_back({a, b, d});
    }
    f.swap(g);
  }
  for (auto& p : v) p = c + r * p;
  return make_mesh(v, f);
}

/// Open n×n-cell sheet over [0, n·h]² in the xy plane with z noise of amplitude `noise`,
/// each cell split into two triangles; a fraction `hole_fraction` of cells (not on the outer
/// ring) is removed to make holes.
inline TriangleMesh noisy_sheet(int n, double h, double noise, double hole_fraction,
                                std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Vec3> v;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      v.emplace_back(i * h, j * h, noise * rng.uniform(-1, 1));
    }
  }
  std::vector<std::array<Index, 3>> f;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const bool inner = i > 0 && j > 0 && i < n - 1 && j < n - 1;
      if (inner && rng.uniform() < hole_fraction) continue;
      const Index a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      f.push_back({a, b, d});
      f.push_back({a, d, c});
    }
  }
  return make_mesh(v, f);
}

/// A random point on a random face of m (uniform barycentrics).
inline Vec3 random_surface_point(const TriangleMesh& m, Rng& rng) {
  const auto f = static_cast<Index>(rng.below(static_cast<std::uint64_t>(m.num_faces())));
  double u = rng.uniform(), w = rng.uniform();
  if (u + w > 1) {
    u = 1 - u;
    w = 1 - w;
  }
  return (1 - u - w) * m.V.row(m.F(f, 0)).transpose() + u * m.V.row(m.F(f, 1)).transpose() +
         w * m.V.row(m.F(f, 2)).transpose();
}

inline Vec3 random_unit(Rng& rng) {
  for (;;) {
    const Vec3 d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const double n = d.norm();
    if (n > 1e-3 && n <= 1.0) return d / n;
  }
}

}  // namespace breastfit::test::spatial_meshes
