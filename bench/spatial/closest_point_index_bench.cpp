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
#include <utility>
#include <vector>

#include "breastfit/core/rng.h"
#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/spatial/closest_point_index.h"
#include "bumpy_ellipsoid.h"

namespace {

using breastfit::Index;
using breastfit::Points;
using breastfit::Rng;
using breastfit::TriangleMesh;
using breastfit::Vec3;
using breastfit::bench::bumpy_ellipsoid;
using breastfit::spatial::ClosestPoint;
using breastfit::spatial::ClosestPointIndex;

constexpr int kNumQueries = 100000;


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

/// Every query warm-started from its hint face.
double query_all_hinted(const ClosestPointIndex& index, const Fixture& fx) {
  double sum = 0.0;
  for (Index i = 0; i < kNumQueries; ++i) {
    sum += index.closest(fx.queries.row(i).transpose(), fx.hint[i]).sq_dist;
  }
  return sum;
}

void BM_QueryHinted100k(benchmark::State& state) {
  const Fixture& fx = fixture();
  const ClosestPointIndex index(fx.mesh);
  for (auto _ : state) benchmark::DoNotOptimize(query_all_hinted(index, fx));
  state.SetItemsProcessed(state.iterations() * kNumQueries);
}
BENCHMARK(BM_QueryHinted100k)->Unit(benchmark::kMillisecond);

/// The same queries on the mesh rounded to float, as scans stored in float PLY files are: the
/// index then keeps the leaves' corners as floats (exact, half the bytes).
const ClosestPointIndex& float_mesh_index() {
  static const ClosestPointIndex index = [] {
    TriangleMesh m = fixture().mesh;
    m.V = m.V.cast<float>().cast<double>();
    return ClosestPointIndex(std::move(m));
  }();
  return index;
}

void BM_Query100kFloatMesh(benchmark::State& state) {
  const Fixture& fx = fixture();
  const ClosestPointIndex& index = float_mesh_index();
  for (auto _ : state) benchmark::DoNotOptimize(query_all(index, fx.queries));
  state.SetItemsProcessed(state.iterations() * kNumQueries);
}
BENCHMARK(BM_Query100kFloatMesh)->Unit(benchmark::kMillisecond);

void BM_QueryHinted100kFloatMesh(benchmark::State& state) {
  const Fixture& fx = fixture();
  const ClosestPointIndex& index = float_mesh_index();
  for (auto _ : state) benchmark::DoNotOptimize(query_all_hinted(index, fx));
  state.SetItemsProcessed(state.iterations() * kNumQueries);
}
BENCHMARK(BM_QueryHinted100kFloatMesh)->Unit(benchmark::kMillisecond);

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
