#pragma once
// A flat (or height-field) square grid for tests: (2n+1)² vertices with spacing `step` mm,
// centred at the origin, counter-clockwise seen from +z (normals +z when flat).
#include <functional>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::test {

/// z = height(x, y) at every vertex (0 without a height function).
TriangleMesh grid_mesh(int n, double step, const std::function<double(double, double)>& height = {});

}  // namespace breastfit::test
