// The scan's skin (fit/skin_around.h skin_vertices: the vertices of the pieces holding at least
// 1 % of the triangles), computed once per scan target by the nipples' checks, and the skin around
// a nipple those checks search its tip and apex on (40 mm), by a pass over every vertex and through
// the scan's index; on a closed bumpy ellipsoid of 327 680 triangles (the bench scans have 150–200
// thousand).
#include <benchmark/benchmark.h>

#include <vector>

#include "breastfit/fit/skin_around.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/spatial/closest_point_index.h"
#include "../spatial/bumpy_ellipsoid.h"

namespace {

using namespace breastfit;

const TriangleMesh& scan() {
  static const TriangleMesh mesh = bench::bumpy_ellipsoid(7);
  return mesh;
}

void BM_SkinVertices(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(fit::skin_vertices(scan()));
  state.counters["triangles"] = static_cast<double>(scan().num_faces());
}
BENCHMARK(BM_SkinVertices)->Unit(benchmark::kMillisecond);

// Arg 0: the pass over every scan vertex; 1: through the scan's index (the checks' way).
void BM_SkinAround(benchmark::State& state) {
  static const spatial::ClosestPointIndex index(scan());
  static const Points normals = mesh::vertex_normals(scan());
  static const std::vector<char> skin = fit::skin_vertices(scan());
  const Vec3 centre = scan().V.row(0).transpose();
  for (auto _ : state) {
    const fit::SkinPatch patch = state.range(0) == 0 ? fit::skin_around(scan(), normals, skin, centre, 40.0)
                                                      : fit::skin_around(index, normals, skin, centre, 40.0);
    benchmark::DoNotOptimize(patch.V.data());
  }
  state.SetLabel(state.range(0) == 0 ? "pass over every vertex" : "through the index");
}
BENCHMARK(BM_SkinAround)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
