#include "breastfit/fit/parallel_chunks.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <vector>

#include <stdlib.h>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace breastfit::fit {
namespace {

#ifdef _OPENMP
// Cores not already busy with other work: the processors minus the whole part of the 1-minute
// load average, at least 1; re-read at most twice a second. A parallel loop waits at its end
// for every thread of its team, so on a machine whose cores are all taken one thread is faster.
int free_cores() {
  using Clock = std::chrono::steady_clock;
  static std::atomic<long long> last_ns{-1};
  static std::atomic<int> last_free{1};
  const long long now = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
  const long long then = last_ns.load(std::memory_order_relaxed);
  if (then >= 0 && now - then < 500'000'000LL) return last_free.load(std::memory_order_relaxed);
  const int cores = std::max(1, omp_get_num_procs());
  double load[1] = {0.0};
  const int busy = getloadavg(load, 1) == 1 && std::isfinite(load[0]) ? static_cast<int>(std::floor(load[0])) : 0;
  const int available = std::clamp(cores - busy, 1, cores);
  last_free.store(available, std::memory_order_relaxed);
  last_ns.store(now, std::memory_order_relaxed);
  return available;
}
#endif

}  // namespace

int resolve_threads(int requested) {
  if (requested > 0) return requested;
#ifdef _OPENMP
  if (std::getenv("OMP_NUM_THREADS")) return std::max(1, omp_get_max_threads());
  return free_cores();
#else
  return 1;
#endif
}

Index num_chunks(Index n, Index chunk_size) { return n <= 0 ? 0 : (n + chunk_size - 1) / chunk_size; }

void for_each_chunk(Index n, Index chunk_size, int threads, const std::function<void(Index, Index, Index)>& fn) {
  const Index chunks = num_chunks(n, chunk_size);
  const int t = static_cast<int>(std::min<Index>(resolve_threads(threads), chunks));
  if (t <= 1) {
    for (Index c = 0; c < chunks; ++c) fn(c, c * chunk_size, std::min(n, (c + 1) * chunk_size));
    return;
  }
  std::vector<std::exception_ptr> errors(static_cast<size_t>(chunks));
#pragma omp parallel for num_threads(t) schedule(dynamic, 1)
  for (Index c = 0; c < chunks; ++c) {
    try {
      fn(c, c * chunk_size, std::min(n, (c + 1) * chunk_size));
    } catch (...) {
      errors[static_cast<size_t>(c)] = std::current_exception();
    }
  }
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace breastfit::fit
