// Where ClosestPointIndex's build time goes, stage by stage, on a large mesh (torso-sized bumpy
// ellipsoid, 327,680 triangles, like a scan) and a small one (5,120 triangles, like the
// template the registration re-indexes every iteration), the large one's build on 1 and 2
// threads, and an index moved to new positions instead of built anew (BM_MoveVertices):
//
//   build-*/bench/index_build_bench --benchmark_repetitions=5 \
//       --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/spatial/closest_point_index.h"
#include "bumpy_ellipsoid.h"
#include "breastfit/spatial/detail/bvh.h"
#include "breastfit/spatial/detail/radix_sort.h"
#include "breastfit/spatial/detail/triangle_tables.h"

namespace {

using breastfit::Index;
using breastfit::TriangleMesh;
using breastfit::Vec3;
using breastfit::bench::bumpy_ellipsoid;
namespace detail = breastfit::spatial::detail;


const TriangleMesh& mesh(int levels) {
  static const TriangleMesh large = bumpy_ellipsoid(7);  // 327,680 triangles
  static const TriangleMesh small = bumpy_ellipsoid(4);  // 5,120 triangles
  return levels == 7 ? large : small;
}

void set_counters(benchmark::State& state, const TriangleMesh& m) {
  state.counters["triangles"] = static_cast<double>(m.num_faces());
}

void BM_IndexBuild(benchmark::State& state) {
  const TriangleMesh& m = mesh(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    breastfit::spatial::ClosestPointIndex index(m);
    benchmark::DoNotOptimize(index);
  }
  set_counters(state, m);
}

// The build on range(1) threads (wall time: the work is spread over the threads; the index is
// the same bits for any number).
void BM_IndexBuildThreads(benchmark::State& state) {
  const TriangleMesh& m = mesh(static_cast<int>(state.range(0)));
  const int threads = static_cast<int>(state.range(1));
  for (auto _ : state) {
    breastfit::spatial::ClosestPointIndex index(m, threads);
    benchmark::DoNotOptimize(index);
  }
  set_counters(state, m);
  state.counters["threads"] = threads;
}

void BM_MeshCopy(benchmark::State& state) {
  const TriangleMesh& m = mesh(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    TriangleMesh copy = m;
    benchmark::DoNotOptimize(copy.V.data());
  }
  set_counters(state, m);
}

void BM_TriangleFlags(benchmark::State& state) {
  const TriangleMesh& m = mesh(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    std::vector<std::uint8_t> vertex_boundary;
    const auto flags = detail::triangle_flags(m, &vertex_boundary);
    benchmark::DoNotOptimize(flags.data());
  }
  set_counters(state, m);
}

void BM_VertexNormals(benchmark::State& state) {
  const TriangleMesh& m = mesh(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const auto normals = breastfit::mesh::vertex_normals(m);
    benchmark::DoNotOptimize(normals.data());
  }
  set_counters(state, m);
}

void BM_MortonOrder(benchmark::State& state) {  // codes + sort
  const TriangleMesh& m = mesh(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const detail::MortonSorted sorted = detail::triangle_morton_order(m);
    benchmark::DoNotOptimize(sorted.prims.data());
  }
  set_counters(state, m);
}

void BM_RadixSort(benchmark::State& state) {  // the sort alone, codes in face order
  const TriangleMesh& m = mesh(static_cast<int>(state.range(0)));
  const detail::MortonSorted sorted = detail::triangle_morton_order(m);
  std::vector<std::uint64_t> codes(sorted.codes.size());
  for (std::size_t i = 0; i < codes.size(); ++i) codes[sorted.prims[i]] = sorted.codes[i];
  for (auto _ : state) {
    std::vector<std::uint64_t> keys = codes;
    const std::vector<std::uint32_t> order = detail::radix_sort_order(keys, 63);
    benchmark::DoNotOptimize(order.data());
  }
  set_counters(state, m);
}

void BM_MortonTopology(benchmark::State& state) {
  const TriangleMesh& m = mesh(static_cast<int>(state.range(0)));
  const detail::MortonSorted sorted = detail::triangle_morton_order(m);
  for (auto _ : state) {
    detail::BvhNodes nodes;
    benchmark::DoNotOptimize(detail::build_morton_topology(sorted.codes, 4, nodes));
  }
  set_counters(state, m);
}

// The index moved to new vertex positions instead of built anew (ClosestPointIndex::move_vertices,
// as the fit's reverse term does at each pose): positions alternating between the mesh's own and
// the mesh bent by a few millimetres (a smooth field), so each call refits the tree.
void BM_MoveVertices(benchmark::State& state) {
  const TriangleMesh& m = mesh(static_cast<int>(state.range(0)));
  breastfit::Points bent = m.V;
  for (Index i = 0; i < bent.rows(); ++i)
    bent.row(i) += 3.0 * Vec3(std::sin(0.02 * m.V(i, 2)), std::cos(0.02 * m.V(i, 0)), 0.5).transpose();
  breastfit::spatial::ClosestPointIndex index(m);
  bool flip = false;
  for (auto _ : state) {
    index.move_vertices((flip = !flip) ? bent : m.V);
    benchmark::DoNotOptimize(index.mesh().V.data());
  }
  set_counters(state, m);
}

#define STAGE(name) BENCHMARK(name)->Arg(7)->Arg(4)->Unit(benchmark::kMicrosecond)
STAGE(BM_IndexBuild);
STAGE(BM_MeshCopy);
STAGE(BM_TriangleFlags);
STAGE(BM_VertexNormals);
STAGE(BM_MortonOrder);
STAGE(BM_RadixSort);
STAGE(BM_MortonTopology);
STAGE(BM_MoveVertices);
BENCHMARK(BM_IndexBuildThreads)->Args({7, 1})->Args({7, 2})->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace
