#pragma once
// Small synthetic meshes for the render and mesh tests (header-only, test code).
#include <cmath>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::test {

/// Axis-aligned cube [-h, h]^3 centred at `c`, 12 outward (counter-clockwise) triangles.
inline TriangleMesh cube_mesh(double h = 0.5, const Vec3& c = Vec3::Zero()) {
  TriangleMesh m;
  m.V.resize(8, 3);
  for (int i = 0; i < 8; ++i)
    m.V.row(i) = (c + Vec3((i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h)).transpose();
  m.F.resize(12, 3);
  m.F << 0, 2, 1, 1, 2, 3,  // z = -h (normal -z)
      4, 5, 6, 5, 7, 6,     // z = +h
      0, 1, 4, 1, 5, 4,     // y = -h
      2, 6, 3, 3, 6, 7,     // y = +h
      0, 4, 2, 2, 4, 6,     // x = -h
      1, 3, 5, 3, 7, 5;     // x = +h
  return m;
}

/// UV sphere of radius r centred at c (outward triangles).
inline TriangleMesh sphere_mesh(double r = 1.0, const Vec3& c = Vec3::Zero(), int n_lat = 48, int n_lon = 96) {
  TriangleMesh m;
  const double pi = 3.14159265358979323846;
  m.V.resize(2 + (n_lat - 1) * n_lon, 3);
  m.V.row(0) = (c + Vec3(0, 0, r)).transpose();
  m.V.row(1) = (c + Vec3(0, 0, -r)).transpose();
  for (int i = 1; i < n_lat; ++i)
    for (int j = 0; j < n_lon; ++j) {
      const double th = pi * i / n_lat, ph = 2 * pi * j / n_lon;
      m.V.row(2 + (i - 1) * n_lon + j) =
          (c + r * Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th))).transpose();
    }
  auto idx = [&](int i, int j) { return static_cast<Index>(2 + (i - 1) * n_lon + (j % n_lon)); };
  std::vector<Eigen::Matrix<Index, 1, 3>> tris;
  for (int j = 0; j < n_lon; ++j) {
    tris.push_back({0, idx(1, j), idx(1, j + 1)});
    tris.push_back({1, idx(n_lat - 1, j + 1), idx(n_lat - 1, j)});
  }
  for (int i = 1; i + 1 < n_lat; ++i)
    for (int j = 0; j < n_lon; ++j) {
      tris.push_back({idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)});
      tris.push_back({idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)});
    }
  m.F.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t k = 0; k < tris.size(); ++k) m.F.row(static_cast<Eigen::Index>(k)) = tris[k];
  return m;
}

/// A square [-h, h]^2 in the plane y = y0 (normal −y, facing an anterior camera at −y).
inline TriangleMesh square_mesh(double h, double y0) {
  TriangleMesh m;
  m.V.resize(4, 3);
  m.V << -h, y0, -h, h, y0, -h, h, y0, h, -h, y0, h;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 2, 3;
  return m;
}

/// `a` with `b`'s vertices and triangles appended (two pieces that share no vertex).
inline TriangleMesh joined_mesh(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V;
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, (b.F.array() + a.V.rows()).matrix();
  return m;
}

/// A breast (a sphere of radius 60 mm at the origin, its front at y = -60) and a floating fragment:
/// a small sphere (radius 3 mm, < 1 % of the triangles) 25 mm in front of it.
inline TriangleMesh breast_with_fragment() {
  return joined_mesh(sphere_mesh(60.0, Vec3::Zero(), 64, 128), sphere_mesh(3.0, Vec3(0, -88, 0), 6, 12));
}

}  // namespace breastfit::test
