#include "breastfit/fit/parallel_chunks.h"

#include <algorithm>
#include <exception>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace breastfit::fit {

int resolve_threads(int requested) {
  if (requested > 0) return requested;
#ifdef _OPENMP
  return std::max(1, omp_get_max_threads());
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
