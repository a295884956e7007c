#pragma once
// A flat (or height-field) square grid for tests: (2n+1)² vertices with spacing `step` mm,
// centred at the origin, counter-clockwise seen from +z (normals +z when flat).
#include <functional>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::test {

/// z = height(x, y) at every vertex (0 without a height function).
TriangleMesh grid_mesh(int n, double step, const std::function<double(double, double)>& height = {});

/// The triangles (two per square) of an m × m grid of vertices numbered row by row (vertex i * m + j
/// at row i, column j), counter-clockwise when rows run along +x and columns along +y.
Triangles grid_triangles(int m);

}  // namespace breastfit::test
