// The scan's skin (fit/skin_around.h skin_vertices: the vertices of the pieces holding at least
// 1 % of the triangles), computed once per fit by the nipples' checks, on a closed bumpy
// ellipsoid of 327 680 triangles (the bench scans have 150–200 thousand).
#include <benchmark/benchmark.h>

#include "breastfit/fit/skin_around.h"
#include "../spatial/bumpy_ellipsoid.h"

namespace {

using namespace breastfit;

void BM_SkinVertices(benchmark::State& state) {
  static const TriangleMesh scan = bench::bumpy_ellipsoid(7);
  for (auto _ : state) benchmark::DoNotOptimize(fit::skin_vertices(scan));
  state.counters["triangles"] = static_cast<double>(scan.num_faces());
}
BENCHMARK(BM_SkinVertices)->Unit(benchmark::kMillisecond);

}  // namespace
