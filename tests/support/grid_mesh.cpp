#include "support/grid_mesh.h"

namespace breastfit::test {

TriangleMesh grid_mesh(int n, double step, const std::function<double(double, double)>& height) {
  const int m = 2 * n + 1;
  TriangleMesh g;
  g.V.resize(m * m, 3);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const double x = (i - n) * step, y = (j - n) * step;
      g.V.row(i * m + j) << x, y, height ? height(x, y) : 0.0;
    }
  g.F = grid_triangles(m);
  return g;
}

Triangles grid_triangles(int m) {
  Triangles F(2 * (m - 1) * (m - 1), 3);
  Index f = 0;
  for (int i = 0; i + 1 < m; ++i)
    for (int j = 0; j + 1 < m; ++j) {
      const Index a = i * m + j, b = (i + 1) * m + j, c = (i + 1) * m + j + 1, d = i * m + j + 1;
      F.row(f++) << a, b, c;
      F.row(f++) << a, c, d;
    }
  return F;
}

}  // namespace breastfit::test
