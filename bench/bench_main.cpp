// The benchmarks' main: the heap settings the `breastfit` program runs with (core/heap_reuse.h:
// freed memory kept and reused, one arena), then Google Benchmark. Without them a benchmark of a
// large allocation mostly measures the kernel's fresh-page faults, which the program does not pay
// on its second and later large blocks (docs/PERFORMANCE.md "Page faults").
#include <benchmark/benchmark.h>

#include "breastfit/core/heap_reuse.h"

int main(int argc, char** argv) {
  breastfit::keep_freed_heap_memory();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
