// Benchmarks of the phases of `breastfit register` around the fit (docs/PERFORMANCE.md), on a
// synthetic case written to a temporary directory (no external data): reading the scan PLY,
// loading the template, preparing the scan, the whole register_scan (fit, transfer,
// measurements) with 1 and 2 threads, painting the scan, the drawings' markups text, and
// writing every output (without report.html).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <string>
#include <unistd.h>

#include "breastfit/io/io.h"
#include "breastfit/io/landmarks_io.h"
#include "breastfit/io/markups.h"
#include "breastfit/model/template_library.h"
#include "breastfit/pipeline/register_outputs.h"
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/synth/case_writer.h"
#include "breastfit/synth/synth_case.h"
#include "registered_case.h"
#include "breastfit/transfer/drawing_outputs.h"

namespace {

using namespace breastfit;
namespace fs = std::filesystem;

struct Fixture : bench::RegisteredCase {
  Fixture() : RegisteredCase("breastfit-phases-bench") {}
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_ReadScanPly(benchmark::State& state) {
  auto& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(io::read_mesh(f.dir / "case" / "scan.ply").V.data());
  state.counters["scan_triangles"] = static_cast<double>(f.request.scan.num_faces());
}
BENCHMARK(BM_ReadScanPly)->Unit(benchmark::kMillisecond);

void BM_LoadTemplate(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(model::load_default_template().rest.V.data());
}
BENCHMARK(BM_LoadTemplate)->Unit(benchmark::kMillisecond);

void BM_PrepareScan(benchmark::State& state) {
  auto& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(pipeline::prepare_scan(f.request.scan, "scan", std::nullopt).to_mm);
}
BENCHMARK(BM_PrepareScan)->Unit(benchmark::kMillisecond);

// Arg: threads.
void BM_RegisterScan(benchmark::State& state) {
  auto& f = fixture();
  pipeline::RegisterRequest req = f.request;
  req.options.threads = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(pipeline::register_scan(req).time_s);
}
BENCHMARK(BM_RegisterScan)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

void BM_PaintScan(benchmark::State& state) {
  auto& f = fixture();
  for (auto _ : state)
    benchmark::DoNotOptimize(transfer::paint_drawings(f.result.scan.mesh_mm, f.result.drawings_on_scan).C.data());
}
BENCHMARK(BM_PaintScan)->Unit(benchmark::kMillisecond);

/// The text of drawings.mrk.json (the largest of the JSON outputs: every drawing's control points).
void BM_FormatDrawingMarkups(benchmark::State& state) {
  auto& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(io::format_markups(f.result.drawings_mm).size());
}
BENCHMARK(BM_FormatDrawingMarkups)->Unit(benchmark::kMillisecond);

/// Arg 0: the outputs of `register --no-report-html`; 1: with report.html, as `register` writes
/// them (the report made on its own thread while the other files are written).
void BM_WriteOutputs(benchmark::State& state) {
  auto& f = fixture();
  pipeline::RegisterOutputOptions o;
  o.report_html = state.range(0) != 0;
  for (auto _ : state) pipeline::write_register_outputs(f.dir / "fit", f.result, *f.model, true, {}, o);
}
BENCHMARK(BM_WriteOutputs)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
