// Benchmarks of the transfer layer after a fit, on a synthetic case made from the shipped default
// template (no external data): the drawings' transfer onto the scan (the workstation's re-fit
// waits for it before its first result) and one breast's volume with a warm volume cache (what
// every re-fit measures twice).
#include <benchmark/benchmark.h>

#include <memory>

#include "breastfit/fit/registration.h"
#include "breastfit/model/template_library.h"
#include "breastfit/pipeline/scan_input.h"
#include "breastfit/synth/synth_case.h"
#include "breastfit/transfer/breast_measurements.h"
#include "breastfit/transfer/drawing_transfer.h"
#include "breastfit/transfer/volume_cache.h"

namespace {

using namespace breastfit;

struct Fixture {
  model::RiggedModel model = model::load_default_template();
  std::unique_ptr<fit::ScanTarget> scan;
  fit::FitResult fitted;

  Fixture() {
    synth::SynthOptions so;
    so.seed = 3;
    const synth::SynthCase c = synth::make_case(model, so);
    const TriangleMesh scan_mm = pipeline::prepare_scan(c.scan, "synth", std::nullopt).mesh_mm;
    std::vector<std::pair<std::string, Vec3>> landmarks_mm;
    const double k = 1.0 / c.scale_mm_to_file_units;
    for (const auto& p : c.input_landmarks) landmarks_mm.emplace_back(p.name, p.position * k);
    const fit::FitOptions options;
    scan = std::make_unique<fit::ScanTarget>(scan_mm, options.correspondences.reverse_samples);
    fitted = fit::register_template(model, *scan, fit::match_landmarks(model, landmarks_mm), options);
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_TransferDrawings(benchmark::State& state) {
  auto& f = fixture();
  size_t points = 0;
  for (auto _ : state) {
    const auto curves = transfer::transfer_drawings(f.model, f.fitted.vertices, *f.scan);
    points = 0;
    for (const auto& c : curves) points += static_cast<size_t>(c.points.rows());
    benchmark::DoNotOptimize(curves.data());
  }
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_TransferDrawings)->Unit(benchmark::kMillisecond);

void BM_BreastSideWarmCache(benchmark::State& state) {
  auto& f = fixture();
  transfer::VolumeCache cache;
  transfer::measure_breast_side(f.model, f.fitted.vertices, 'R', {}, &cache);  // warm: as after the first fit
  for (auto _ : state) {
    const auto side = transfer::measure_breast_side(f.model, f.fitted.vertices, 'R', {}, &cache);
    benchmark::DoNotOptimize(&side);
  }
}
BENCHMARK(BM_BreastSideWarmCache)->Unit(benchmark::kMillisecond);

}  // namespace
