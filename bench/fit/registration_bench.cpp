// Benchmarks of the registration's parts and of a whole fit, on a synthetic case made from the
// shipped default template (no external data): scan index build, correspondences (at the
// landmark-initialised pose and at the fitted one), the arm search
// of the initialisation, normal equations assembly (with and without the blendshapes), one damped
// LM step's solve, one LM iteration, posing the template, the placed landmarks' leave-one-out predictions, the surface-detail layer, and the full registration (what report.json's time_s
// measures); the parallel parts with 1 and 2 threads (the last argument).
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "breastfit/fit/stage_minimizer.h"
#include "breastfit/fit/problem.h"
#include "breastfit/fit/registration.h"
#include "breastfit/fit/surface_detail.h"
#include "breastfit/fit/initialization.h"
#include "breastfit/fit/landmark_prediction.h"
#include "breastfit/fit/lm_strategy.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/model/pose_evaluator.h"
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

  /// The parameters a full registration fits (computed once, on first use).
  const model::PoseParams& fitted() {
    static const model::PoseParams p = fit::register_template(model, *scan, targets, options).params;
    return p;
  }

  /// A problem at the landmark-initialised pose (`o`: its options, kept by reference).
  std::unique_ptr<fit::Problem> problem(const fit::FitOptions& o) {
    auto p = std::make_unique<fit::Problem>(model, *scan, o, targets);
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

// Options with `threads` threads (fit/parallel_chunks.h).
fit::FitOptions with_threads(const fit::FitOptions& o, int64_t threads) {
  fit::FitOptions out = o;
  out.threads = static_cast<int>(threads);
  return out;
}

// The correspondence benchmarks' label: which directions (range(0)), how many threads (range(1)).
void label_search(benchmark::State& state) {
  state.SetLabel(std::string(state.range(0) ? "model->scan + scan->model" : "model->scan") + ", " +
                 std::to_string(state.range(1)) + " threads");
}

// Args: (with the reverse term, threads).
void BM_Correspondences(benchmark::State& state) {
  auto& f = fixture();
  const fit::FitOptions options = with_threads(f.options, state.range(1));
  const auto problem_ptr = f.problem(options);
  fit::Problem& problem = *problem_ptr;
  for (auto _ : state) {
    problem.clear_correspondences();  // else the memo keeps the pairs of the same pose
    problem.update_correspondences(20.0, 1, state.range(0) != 0);
  }
  state.counters["model_vertices"] = f.model.num_vertices();
  label_search(state);
}
BENCHMARK(BM_Correspondences)->Args({0, 1})->Args({1, 1})->Args({0, 2})->Args({1, 2})->Unit(benchmark::kMillisecond);

// The searches of a late iteration: at the fitted parameters and at the same moved by 0.5 mm,
// alternately (each search warm-started from the other pose's answers, as a stage's next search
// starts from its last one), at the refine stage's threshold (15 mm), every vertex. Args: (with the
// reverse term, threads). The landmark-initialised pose of BM_Correspondences is far from the
// scan (searches there test more triangles); a fit's searches are mostly like these.
void BM_CorrespondencesAtFit(benchmark::State& state) {
  auto& f = fixture();
  const fit::FitOptions options = with_threads(f.options, state.range(1));
  const auto problem_ptr = f.problem(options);
  fit::Problem& problem = *problem_ptr;
  model::PoseParams poses[2] = {f.fitted(), f.fitted()};
  poses[1].global.translation += Vec3(0.3, -0.3, 0.3);
  int k = 0;
  for (auto _ : state) {
    problem.evaluator().set_params(poses[k ^= 1]);
    problem.update_correspondences(options.correspondences.max_distance_end_mm, 1, state.range(0) != 0);
  }
  problem.evaluator().set_params(poses[0]);
  problem.update_correspondences(options.correspondences.max_distance_end_mm, 1, state.range(0) != 0);
  state.counters["kept"] = static_cast<double>(problem.pairs().size());  // at the fitted pose
  state.counters["queries_per_s"] =
      benchmark::Counter(static_cast<double>(f.model.num_vertices()), benchmark::Counter::kIsIterationInvariantRate);
  label_search(state);
}
BENCHMARK(BM_CorrespondencesAtFit)->Args({0, 1})->Args({1, 1})->Args({0, 2})->Args({1, 2})->Unit(benchmark::kMillisecond);

// The arms' angle search of the initialisation (28 posed arms scored against the scan), with
// `threads` threads.
void BM_ArmSearch(benchmark::State& state) {
  auto& f = fixture();
  for (auto _ : state) {
    model::PoseParams params = f.start;
    benchmark::DoNotOptimize(fit::initialize_arms(f.model, *f.scan, params, false, static_cast<int>(state.range(0))));
  }
}
BENCHMARK(BM_ArmSearch)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_NormalEquationsAssembly(benchmark::State& state) {
  auto& f = fixture();
  const fit::FitOptions options = with_threads(f.options, state.range(0));
  const auto problem_ptr = f.problem(options);
  fit::Problem& problem = *problem_ptr;
  problem.update_correspondences(20.0, 1, true);
  fit::NormalEquations eq(problem.evaluator().layout().num_params());
  // Second argument 0: the pose stage's parameters (no blendshapes: their Jacobian entries are
  // left out); 1: every parameter (the shape and refine stages).
  if (state.range(1) == 0) eq.set_active(fit::active_parameters(problem.evaluator().layout(), options.pose, -1));
  for (auto _ : state) {
    eq.clear();
    problem.evaluate(&eq);
    eq.finalize();
    benchmark::DoNotOptimize(eq.H().data());
  }
  state.counters["params"] = eq.size();
  state.counters["pairs"] = problem.pairs().size();
  state.counters["threads"] = static_cast<double>(state.range(0));
}
BENCHMARK(BM_NormalEquationsAssembly)
    ->Args({1, 1})
    ->Args({2, 1})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Unit(benchmark::kMillisecond);

// Posing the template (PoseEvaluator::set_params) for parameters that alternate between two sets,
// as an LM step tried and taken does: with range(0) 0 only the pose differs (the landmark_pose,
// rigid and pose stages), with 1 the blendshape weights too (shape, refine).
void BM_SetParams(benchmark::State& state) {
  auto& f = fixture();
  model::PoseEvaluator ev(f.model);
  model::PoseParams a = f.start;
  a.alpha.setConstant(0.1);
  model::PoseParams b = a;
  b.global.translation += Vec3(1.0, -0.5, 0.25);
  b.bones[0].scale *= 1.01;
  if (state.range(0) == 1) b.alpha.setConstant(0.12);
  bool flip = false;
  for (auto _ : state) {
    ev.set_params(flip ? a : b);
    flip = !flip;
    benchmark::DoNotOptimize(ev.vertices().data());
  }
  state.counters["vertices"] = static_cast<double>(f.model.num_vertices());
}
BENCHMARK(BM_SetParams)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The 12 leave-one-out predictions of the placed-landmark checks (predict_left_out_landmarks: one
// assembly and factorisation, a low-rank solve and the landmark's posing per landmark) at the
// fitted parameters and the final correspondences, with 1 and 2 threads (the assembly's).
void BM_LeaveOneOutPredictions(benchmark::State& state) {
  auto& f = fixture();
  const fit::FitOptions options = with_threads(f.options, state.range(0));
  const model::PoseParams& fitted = f.fitted();
  const auto problem = f.problem(options);
  problem->evaluator().set_params(fitted);
  problem->update_correspondences(options.correspondences.max_distance_end_mm, 1, options.uses_reverse_term());
  problem->update_terms(options.refine.robust_landmarks);
  const auto active = fit::active_parameters(problem->evaluator().layout(), options.refine, options.max_blendshapes);
  for (auto _ : state) {
    const auto predicted = fit::predict_left_out_landmarks(*problem, fitted, active);
    benchmark::DoNotOptimize(predicted.data());
  }
  state.counters["landmarks"] = static_cast<double>(f.targets.size());
}
BENCHMARK(BM_LeaveOneOutPredictions)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// One damped Levenberg–Marquardt step (LevenbergMarquardtStrategy::compute_step: damping, the
// LDLT factorisation, the solve) on the normal equations of every parameter (the shape and refine
// stages' system), as each tried step of a stage solves it.
void BM_LmStep(benchmark::State& state) {
  auto& f = fixture();
  const fit::FitOptions options = with_threads(f.options, 1);
  const auto problem = f.problem(options);
  problem->update_correspondences(20.0, 1, true);
  fit::NormalEquations eq(problem->evaluator().layout().num_params());
  eq.clear();
  problem->evaluate(&eq);
  eq.finalize();
  const Eigen::MatrixXd H = eq.H();
  fit::LevenbergMarquardtStrategy lm(options.solver);
  for (auto _ : state) benchmark::DoNotOptimize(lm.compute_step(H, eq.g()).x.data());
  state.counters["params"] = static_cast<double>(H.rows());
}
BENCHMARK(BM_LmStep)->Unit(benchmark::kMicrosecond);

void BM_OneLmIteration(benchmark::State& state) {
  auto& f = fixture();
  fit::StageOptions stage{"bench", true, true, true, 1, 1};
  const fit::FitOptions options = with_threads(f.options, state.range(0));
  for (auto _ : state) {
    const auto problem = f.problem(options);
    model::PoseParams p = f.start;
    fit::FitSummary s;
    fit::minimize_stages(*problem, {stage}, p, s);
    benchmark::DoNotOptimize(p.global.scale);
  }
}
BENCHMARK(BM_OneLmIteration)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_SurfaceDetail(benchmark::State& state) {
  auto& f = fixture();
  fit::FitOptions no_detail;
  no_detail.detail.enabled = false;
  const auto fitted = fit::register_template(f.model, *f.scan, f.targets, no_detail);
  int kept = 0;
  for (auto _ : state) {
    const auto d = fit::fit_surface_detail(fitted.vertices, f.model.rest.F, *f.scan, f.options.correspondences,
                                           f.options.detail, static_cast<int>(state.range(0)));
    kept = d.kept;
    benchmark::DoNotOptimize(d.offsets.data());
  }
  state.counters["kept"] = kept;
}
BENCHMARK(BM_SurfaceDetail)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_FullRegistration(benchmark::State& state) {
  auto& f = fixture();
  int iterations = 0;
  const fit::FitOptions options = with_threads(fit::FitOptions{}, state.range(0));
  for (auto _ : state) {
    fit::ScanTarget scan(f.scan_mm, options.correspondences.reverse_samples);  // index build included
    const auto r = fit::register_template(f.model, scan, fit::match_landmarks(f.model, f.landmarks_mm), options);
    iterations = static_cast<int>(r.summary.iterations.size());
    benchmark::DoNotOptimize(r.vertices.data());
  }
  state.counters["lm_iterations"] = iterations;
}
BENCHMARK(BM_FullRegistration)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace
