// Benchmarks of report.html (docs/PERFORMANCE.md, docs/REPORT.md) on a synthetic case written to
// a temporary directory (no external data): the six figures (sequential and concurrent), one
// overlay figure's rendering alone (front or side), the scan layers drawn before the fit and the
// rest after it, PNG encoding of a front figure, and the HTML with its base64 images.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>

#include "breastfit/pipeline/report_figures.h"
#include "breastfit/pipeline/report_html.h"
#include "breastfit/pipeline/report_layers.h"
#include "breastfit/render/scene.h"
#include "registered_case.h"

namespace {

using namespace breastfit;

struct Fixture : bench::RegisteredCase {
  pipeline::ReportFigures figures;
  Fixture() : RegisteredCase("breastfit-report-bench") { figures = pipeline::render_report_figures(result); }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

// Arg: 1 = figures rendered concurrently, 0 = one after the other.
void BM_ReportFigures(benchmark::State& state) {
  auto& f = fixture();
  pipeline::ReportFigureOptions o;
  o.parallel = state.range(0) != 0;
  for (auto _ : state) benchmark::DoNotOptimize(pipeline::render_report_figures(f.result, o).figures.size());
  state.counters["scan_triangles"] = static_cast<double>(f.result.scan.mesh_mm.num_faces());
}
BENCHMARK(BM_ReportFigures)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// One overlay figure's pixels (scene built once), without PNG encoding. Arg: 0 = the front
// figure (900², supersampled), 1 = a side figure (450²).
void BM_RenderOverlay(benchmark::State& state) {
  auto& f = fixture();
  const bool side = state.range(0) != 0;
  pipeline::ReportFigureOptions o;
  if (side) {
    o.size = o.side_size;
    o.text_scale = std::max(1, o.text_scale / 2);
  }
  const render::Scene scene = pipeline::overlay_scene(f.result, o);
  render::RenderOptions ro;
  ro.width = ro.height = o.size;
  ro.supersample = o.supersample;
  ro.text_scale = o.text_scale;
  ro.body_to_world = f.figures.body_to_world;
  ro.view = side ? render::View::Side : render::View::Front;
  for (auto _ : state) benchmark::DoNotOptimize(render::render_scene(scene, ro).bytes().data());
}
BENCHMARK(BM_RenderOverlay)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The preparation before any overlay figure: the scan cropped near the fit, its normals, the
// drawings and landmarks (one scene).
void BM_OverlayScene(benchmark::State& state) {
  auto& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(pipeline::overlay_scene(f.result).meshes.size());
}
BENCHMARK(BM_OverlayScene)->Unit(benchmark::kMillisecond);

// The report's path with landmarks (report_layers.h). Arg 0: the five overlay figures' scan
// layers drawn on one thread (what `register` draws beside the fit), the setup included;
// Arg 1: the rest, after the fit, over layers drawn beforehand by a ReportLayerDrawing (the
// overlays, the distance figure and the six PNGs, concurrently as `register` does).
void BM_ReportLayers(benchmark::State& state) {
  auto& f = fixture();
  const pipeline::ReportFigureOptions o;
  const bool after_fit = state.range(0) != 0;
  for (auto _ : state) {
    if (!after_fit) {
      const auto layers = pipeline::plan_report_layers(f.result, *f.model, o);
      for (size_t k = 0; k < pipeline::kOverlayFigures; ++k)
        benchmark::DoNotOptimize(pipeline::draw_report_layer(*layers, k, o).surface_coverage());
      continue;
    }
    state.PauseTiming();
    auto drawing = std::make_shared<pipeline::ReportLayerDrawing>(
        [&] { return pipeline::plan_report_layers(f.result, *f.model, o); }, o);
    drawing->wait();
    state.ResumeTiming();
    benchmark::DoNotOptimize(pipeline::report_figures(f.result, *f.model, o, drawing).figures.size());
  }
}
BENCHMARK(BM_ReportLayers)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_EncodeFrontPng(benchmark::State& state) {
  auto& f = fixture();
  const render::Image& img = f.figures.figures.front().image;
  size_t bytes = 0;
  for (auto _ : state) bytes = img.encode_png().size();
  state.counters["png_kB"] = static_cast<double>(bytes) / 1000.0;
}
BENCHMARK(BM_EncodeFrontPng)->Unit(benchmark::kMillisecond);

void BM_ReportHtml(benchmark::State& state) {
  auto& f = fixture();
  size_t bytes = 0;
  for (auto _ : state) bytes = pipeline::report_html(f.result, f.model->name, f.figures).size();
  state.counters["html_kB"] = static_cast<double>(bytes) / 1000.0;
}
BENCHMARK(BM_ReportHtml)->Unit(benchmark::kMillisecond);

}  // namespace
