// The nipple's bump searched on the scan (fit/nipple_bump.h), as the placed-landmark checks search
// it around each given nipple: through the scan's index, on a breast-like dome as dense as the
// scans on the breast (0.5 mm, 4 vertices per mm²) with a nipple-sized bump 12 mm from the centre.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "breastfit/fit/nipple_bump.h"
#include "breastfit/spatial/closest_point_index.h"

namespace {

using namespace breastfit;

struct Fixture {
  TriangleMesh dome;
  Points normals;
  std::unique_ptr<spatial::ClosestPointIndex> index;

  // A sphere cap (radius 90 mm, +z outward) over 120 × 120 mm with a Gaussian bump (5 mm high,
  // σ 3 mm) at (8, −9), as a height field triangulated two triangles per grid square.
  Fixture() {
    const double step = 0.5, half = 60.0, R = 90.0;
    const int n = static_cast<int>(2 * half / step) + 1;
    dome.V.resize(n * n, 3);
    normals.resize(n * n, 3);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double x = -half + i * step, y = -half + j * step;
        const double d2 = (x - 8.0) * (x - 8.0) + (y + 9.0) * (y + 9.0);
        const double z = std::sqrt(R * R - x * x - y * y) - R + 5.0 * std::exp(-d2 / 18.0);
        dome.V.row(i * n + j) << x, y, z;
        normals.row(i * n + j) = Vec3(x, y, z + R).normalized().transpose();
      }
    dome.F.resize(2 * (n - 1) * (n - 1), 3);
    Index f = 0;
    for (int i = 0; i + 1 < n; ++i)
      for (int j = 0; j + 1 < n; ++j) {
        const Index a = i * n + j, b = a + 1, c = a + n, d = c + 1;
        dome.F.row(f++) << a, c, b;
        dome.F.row(f++) << b, c, d;
      }
    index = std::make_unique<spatial::ClosestPointIndex>(dome);
  }
};

const Fixture& fixture() {
  static const Fixture fx;
  return fx;
}

// One nipple's search (what check_anatomy's search_nipples does per given nipple).
void BM_NippleBumpOnScan(benchmark::State& state) {
  const Fixture& fx = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(fit::nipple_bump_on_scan(*fx.index, fx.normals, Vec3::Zero()));
}
BENCHMARK(BM_NippleBumpOnScan)->Unit(benchmark::kMillisecond);

}  // namespace
