#include "breastfit/spatial/detail/parallel_for.h"

#include <algorithm>

#include "breastfit/core/chunk_pool.h"

namespace breastfit::spatial::detail {

void parallel_for_chunks(std::size_t n, std::size_t chunk_size, int threads,
                         const std::function<void(std::size_t, std::size_t, std::size_t)>& fn) {
  const std::size_t chunks = chunk_count(n, chunk_size);
  const auto t = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), chunks));
  run_chunks(chunks, t, [&](std::size_t c) { fn(c, c * chunk_size, std::min(n, (c + 1) * chunk_size)); });
}

void parallel_invoke(int threads, const std::function<void()>& first, const std::function<void()>& second) {
  run_chunks(2, std::min(threads, 2), [&](std::size_t c) { c == 0 ? first() : second(); });
}

}  // namespace breastfit::spatial::detail
