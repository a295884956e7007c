// Benchmarks of the registration's parts and of a whole fit, on a synthetic case made from the
// shipped default template (no external data): scan index build, correspondences, normal
// equations assembly, one LM iteration, the surface-detail layer, and the full registration (what report.json's time_s
// measures).
#include <benchmark/benchmark.h>

#include <memory>

#include "breastfit/fit/stage_minimizer.h"
#include "breastfit/fit/problem.h"
#include "breastfit/fit/registration.h"
#include "breastfit/fit/surface_detail.h"
#include "breastfit/fit/initialization.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/model/template_library.h"
#include "breastfit/pipeline/scan_input.h"
#include "breastfit/synth/synth_case.h"

namespace {

using namespace breastfit;

struct Fixture {
  model::RiggedModel model = model::load_default_template();
  synth::SynthCase c;
  TriangleMesh scan_mm;
  std::vector<std::pair<std::string, Vec3>> landmarks_mm;
  model::PoseParams start;
  std::unique_ptr<fit::ScanTarget> scan;
  fit::FitOptions options;
  std::vector<fit::LandmarkTarget> targets;

  Fixture() {
    synth::SynthOptions so;
    so.seed = 3;
    c = synth::make_case(model, so);
    scan_mm = pipeline::prepare_scan(c.scan, "synth", std::nullopt).mesh_mm;
    const double k = 1.0 / c.scale_mm_to_file_units;
    for (const auto& p : c.input_landmarks) landmarks_mm.emplace_back(p.name, p.position * k);
    targets = fit::match_landmarks(model, landmarks_mm);
    start = model::PoseParams::identity(model);
    start.global = fit::initialize_from_landmarks(model, targets).similarity;
    scan = std::make_unique<fit::ScanTarget>(scan_mm, options.correspondences.reverse_samples);
  }

  /// A problem at the landmark-initialised pose.
  std::unique_ptr<fit::Problem> problem() {
    auto p = std::make_unique<fit::Problem>(model, *scan, options, targets);
    p->evaluator().set_params(start);
    return p;
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_ScanIndexBuild(benchmark::State& state) {
  auto& f = fixture();
  for (auto _ : state) {
    fit::ScanTarget scan(f.scan_mm, 800);
    benchmark::DoNotOptimize(scan.sample_points().data());
  }
  state.counters["scan_triangles"] = f.scan_mm.num_faces();
}
BENCHMARK(BM_ScanIndexBuild)->Unit(benchmark::kMillisecond);

void BM_Correspondences(benchmark::State& state) {
  auto& f = fixture();
  const auto problem_ptr = f.problem();
  fit::Problem& problem = *problem_ptr;
  for (auto _ : state) problem.update_correspondences(20.0, 1, state.range(0) != 0);
  state.counters["model_vertices"] = f.model.num_vertices();
  state.SetLabel(state.range(0) ? "model->scan + scan->model" : "model->scan");
}
BENCHMARK(BM_Correspondences)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_NormalEquationsAssembly(benchmark::State& state) {
  auto& f = fixture();
  const auto problem_ptr = f.problem();
  fit::Problem& problem = *problem_ptr;
  problem.update_correspondences(20.0, 1, true);
  fit::NormalEquations eq(problem.evaluator().layout().num_params());
  for (auto _ : state) {
    eq.clear();
    problem.evaluate(&eq);
    eq.finalize();
    benchmark::DoNotOptimize(eq.H().data());
  }
  state.counters["params"] = eq.size();
  state.counters["pairs"] = problem.pairs().size();
}
BENCHMARK(BM_NormalEquationsAssembly)->Unit(benchmark::kMillisecond);

void BM_OneLmIteration(benchmark::State& state) {
  auto& f = fixture();
  fit::StageOptions stage{"bench", true, true, true, 1, 1};
  for (auto _ : state) {
    const auto problem = f.problem();
    model::PoseParams p = f.start;
    fit::FitSummary s;
    fit::minimize_stages(*problem, {stage}, p, s);
    benchmark::DoNotOptimize(p.global.scale);
  }
}
BENCHMARK(BM_OneLmIteration)->Unit(benchmark::kMillisecond);

void BM_SurfaceDetail(benchmark::State& state) {
  auto& f = fixture();
  fit::FitOptions no_detail;
  no_detail.detail.enabled = false;
  const auto fitted = fit::register_template(f.model, *f.scan, f.targets, no_detail);
  int kept = 0;
  for (auto _ : state) {
    const auto d = fit::fit_surface_detail(fitted.vertices, f.model.rest.F, *f.scan, f.options.correspondences,
                                           f.options.detail);
    kept = d.kept;
    benchmark::DoNotOptimize(d.offsets.data());
  }
  state.counters["kept"] = kept;
}
BENCHMARK(BM_SurfaceDetail)->Unit(benchmark::kMillisecond);

void BM_FullRegistration(benchmark::State& state) {
  auto& f = fixture();
  int iterations = 0;
  for (auto _ : state) {
    fit::ScanTarget scan(f.scan_mm, fit::FitOptions{}.correspondences.reverse_samples);  // index build included
    const auto r = fit::register_template(f.model, scan, fit::match_landmarks(f.model, f.landmarks_mm), {});
    iterations = static_cast<int>(r.summary.iterations.size());
    benchmark::DoNotOptimize(r.vertices.data());
  }
  state.counters["lm_iterations"] = iterations;
}
BENCHMARK(BM_FullRegistration)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
