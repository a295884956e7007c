#include "breastfit/fit/parallel_chunks.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>

#include <stdlib.h>

#include "breastfit/core/chunk_pool.h"

namespace breastfit::fit {
namespace {

// Cores not already busy with other work: the processors minus the whole part of the 1-minute
// load average, at least 1; re-read at most twice a second. A parallel loop waits at its end
// for the chunks its threads have taken, so on a machine whose cores are all taken one thread is
// faster.
int free_cores() {
  using Clock = std::chrono::steady_clock;
  static std::atomic<long long> last_ns{-1};
  static std::atomic<int> last_free{1};
  const long long now = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
  const long long then = last_ns.load(std::memory_order_relaxed);
  if (then >= 0 && now - then < 500'000'000LL) return last_free.load(std::memory_order_relaxed);
  const int cores = available_processors();
  double load[1] = {0.0};
  const int busy = getloadavg(load, 1) == 1 && std::isfinite(load[0]) ? static_cast<int>(std::floor(load[0])) : 0;
  const int available = std::clamp(cores - busy, 1, cores);
  last_free.store(available, std::memory_order_relaxed);
  last_ns.store(now, std::memory_order_relaxed);
  return available;
}

// OMP_NUM_THREADS (its first number, as OpenMP reads it), or 0 when unset or not a number.
int threads_from_environment() {
  const char* text = std::getenv("OMP_NUM_THREADS");
  if (!text) return 0;
  char* end = nullptr;
  const long n = std::strtol(text, &end, 10);
  return end != text && n > 0 ? static_cast<int>(std::min<long>(n, 1024)) : 0;
}

}  // namespace

int resolve_threads(int requested) {
  if (requested > 0) return requested;
  if (const int n = threads_from_environment(); n > 0) return n;
  return free_cores();
}

Index num_chunks(Index n, Index chunk_size) { return n <= 0 ? 0 : (n + chunk_size - 1) / chunk_size; }

void for_each_chunk(Index n, Index chunk_size, int threads, const std::function<void(Index, Index, Index)>& fn) {
  const Index chunks = num_chunks(n, chunk_size);
  const int t = static_cast<int>(std::min<Index>(resolve_threads(threads), chunks));
  run_chunks(static_cast<std::size_t>(chunks), t, [&](std::size_t chunk) {
    const auto c = static_cast<Index>(chunk);
    fn(c, c * chunk_size, std::min(n, (c + 1) * chunk_size));
  });
}

}  // namespace breastfit::fit
