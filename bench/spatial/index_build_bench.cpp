// Where ClosestPointIndex's build time goes, stage by stage, on a large mesh (torso-sized bumpy
// ellipsoid, 327,680 triangles, like a scan) and a small one (5,120 triangles, like the
// template the registration re-indexes every iteration):
//
//   build-*/bench/index_build_bench --benchmark_repetitions=5 \
//       --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/spatial/closest_point_index.h"
#include "breastfit/spatial/detail/bvh.h"
#include "breastfit/spatial/detail/radix_sort.h"
#include "breastfit/spatial/detail/triangle_tables.h"

namespace {

using breastfit::Index;
using breastfit::TriangleMesh;
using breastfit::Vec3;
namespace detail = breastfit::spatial::detail;

/// Icosphere with `levels` subdivisions (20·4^levels triangles, shared vertices), mapped onto
/// an ellipsoid with semi-axes (150, 100, 200) mm with a few percent of smooth bumps.
TriangleMesh bumpy_ellipsoid(int levels) {
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
    std::map<std::uint64_t, Index> mid;  // edge (sorted endpoints) → midpoint vertex
    auto shared_mid = [&](Index a, Index b) {
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
                                static_cast<std::uint32_t>(std::max(a, b));
      const auto [it, inserted] = mid.emplace(key, static_cast<Index>(v.size()));
      if (inserted) v.push_back((v[a] + v[b]).normalized());
      return it->second;
    };
    std::vector<std::array<Index, 3>> g;
    g.reserve(4 * f.size());
    for (const auto& tri : f) {
      const Index a = shared_mid(tri[0], tri[1]), b = shared_mid(tri[1], tri[2]),
                  c = shared_mid(tri[2], tri[0]);
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
    const auto normals = detail::area_weighted_vertex_normals(m);
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
    std::vector<std::uint32_t> values(keys.size());
    detail::radix_sort_pairs(keys, values, 63);
    benchmark::DoNotOptimize(keys.data());
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

#define STAGE(name) BENCHMARK(name)->Arg(7)->Arg(4)->Unit(benchmark::kMicrosecond)
STAGE(BM_IndexBuild);
STAGE(BM_MeshCopy);
STAGE(BM_TriangleFlags);
STAGE(BM_VertexNormals);
STAGE(BM_MortonOrder);
STAGE(BM_RadixSort);
STAGE(BM_MortonTopology);

}  // namespace

BENCHMARK_MAIN();
