// Closest-point index on a torso-sized bumpy ellipsoid (~300 × 200 × 400 mm, 327,680 triangles):
// build time, single-thread query throughput for 100k queries within 5 mm of the surface, and
// build + 100k queries. Results are recorded in docs/SPATIAL.md.
//
//   build-*/bench/closest_point_index_bench --benchmark_repetitions=5 \
//       --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "breastfit/core/rng.h"
#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/spatial/closest_point_index.h"

namespace {

using breastfit::Index;
using breastfit::Points;
using breastfit::Rng;
using breastfit::TriangleMesh;
using breastfit::Vec3;
using breastfit::spatial::ClosestPoint;
using breastfit::spatial::ClosestPointIndex;

constexpr int kNumQueries = 100000;

/// Icosphere subdivided `levels` times (20·4^levels triangles), then mapped onto an ellipsoid
/// with semi-axes (150, 100, 200) mm and a few percent of smooth bumps.
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
    std::unordered_map<std::uint64_t, Index> mid;
    mid.reserve(f.size() * 2);
    auto midpoint = [&](Index a, Index b) {
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) |
                                static_cast<std::uint32_t>(std::max(a, b));
      const auto [it, inserted] = mid.emplace(key, static_cast<Index>(v.size()));
      if (inserted) v.push_back((v[a] + v[b]).normalized());
      return it->second;
    };
    std::vector<std::array<Index, 3>> g;
    g.reserve(4 * f.size());
    for (const auto& tri : f) {
      const Index a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]),
                  c = midpoint(tri[2], tri[0]);
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

struct Fixture {
  TriangleMesh mesh = bumpy_ellipsoid(7);
  Points queries;           // 100k points within 5 mm of the surface, random order
  std::vector<Index> hint;  // closest face of each query moved by up to 0.5 mm ("last iteration")

  Fixture() {
    Rng rng(20261121);
    queries.resize(kNumQueries, 3);
    for (int i = 0; i < kNumQueries; ++i) {
      const auto f = static_cast<Index>(rng.below(static_cast<std::uint64_t>(mesh.num_faces())));
      double u = rng.uniform(), w = rng.uniform();
      if (u + w > 1) {
        u = 1 - u;
        w = 1 - w;
      }
      const Vec3 p = (1 - u - w) * mesh.V.row(mesh.F(f, 0)).transpose() +
                     u * mesh.V.row(mesh.F(f, 1)).transpose() +
                     w * mesh.V.row(mesh.F(f, 2)).transpose();
      Vec3 d(rng.normal(), rng.normal(), rng.normal());
      d.normalize();
      queries.row(i) = p + rng.uniform(0, 5.0) * d;
    }
    const ClosestPointIndex index(mesh);
    hint.resize(kNumQueries);
    for (int i = 0; i < kNumQueries; ++i) {
      Vec3 d(rng.normal(), rng.normal(), rng.normal());
      d.normalize();
      hint[i] = index.closest(Vec3(queries.row(i).transpose()) + rng.uniform(0, 0.5) * d).face;
    }
  }
};

const Fixture& fixture() {
  static const Fixture fx;
  return fx;
}

void BM_Build(benchmark::State& state) {
  const Fixture& fx = fixture();
  for (auto _ : state) {
    ClosestPointIndex index(fx.mesh);
    benchmark::DoNotOptimize(index);
  }
  state.counters["triangles"] = static_cast<double>(fx.mesh.num_faces());
}
BENCHMARK(BM_Build)->Unit(benchmark::kMillisecond);

double query_all(const ClosestPointIndex& index, const Points& Q) {
  double sum = 0.0;
  for (Index i = 0; i < Q.rows(); ++i) sum += index.closest(Q.row(i).transpose()).sq_dist;
  return sum;
}

void BM_Query100k(benchmark::State& state) {
  const Fixture& fx = fixture();
  const ClosestPointIndex index(fx.mesh);
  for (auto _ : state) benchmark::DoNotOptimize(query_all(index, fx.queries));
  state.SetItemsProcessed(state.iterations() * kNumQueries);
}
BENCHMARK(BM_Query100k)->Unit(benchmark::kMillisecond);

void BM_QueryWithin6mm100k(benchmark::State& state) {
  const Fixture& fx = fixture();
  const ClosestPointIndex index(fx.mesh);
  for (auto _ : state) {
    double sum = 0.0;
    for (Index i = 0; i < kNumQueries; ++i) {
      const auto cp = index.closest_within(fx.queries.row(i).transpose(), 6.0);
      sum += cp ? cp->sq_dist : 0.0;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * kNumQueries);
}
BENCHMARK(BM_QueryWithin6mm100k)->Unit(benchmark::kMillisecond);

void BM_QueryHinted100k(benchmark::State& state) {
  const Fixture& fx = fixture();
  const ClosestPointIndex index(fx.mesh);
  for (auto _ : state) {
    double sum = 0.0;
    for (Index i = 0; i < kNumQueries; ++i) {
      sum += index.closest(fx.queries.row(i).transpose(), fx.hint[i]).sq_dist;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * kNumQueries);
}
BENCHMARK(BM_QueryHinted100k)->Unit(benchmark::kMillisecond);

void BM_QueryBatch100k(benchmark::State& state) {
  const Fixture& fx = fixture();
  const ClosestPointIndex index(fx.mesh);
  for (auto _ : state) {
    std::vector<ClosestPoint> out = index.closest_batch(fx.queries);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * kNumQueries);
}
BENCHMARK(BM_QueryBatch100k)->Unit(benchmark::kMillisecond);

void BM_BuildPlus100kQueries(benchmark::State& state) {
  const Fixture& fx = fixture();
  for (auto _ : state) {
    const ClosestPointIndex index(fx.mesh);
    benchmark::DoNotOptimize(query_all(index, fx.queries));
  }
  state.SetItemsProcessed(state.iterations() * kNumQueries);
}
BENCHMARK(BM_BuildPlus100kQueries)->Unit(benchmark::kMillisecond);

void BM_BuildPlus100kBatch(benchmark::State& state) {
  const Fixture& fx = fixture();
  for (auto _ : state) {
    const ClosestPointIndex index(fx.mesh);
    std::vector<ClosestPoint> out = index.closest_batch(fx.queries);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * kNumQueries);
}
BENCHMARK(BM_BuildPlus100kBatch)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
