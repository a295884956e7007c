#pragma once
/// \file Deterministic parallel loop of the spatial layer's index builds (the process's worker
/// pool, core/chunk_pool.h; private to the layer). [0, n) is cut into chunks of a fixed size; each chunk runs once, on up to `threads`
/// threads in any order, and writes only its own slots, so a build gives the same bits whatever
/// the thread count.
#include <cstddef>
#include <functional>

namespace breastfit::spatial::detail {

/// Calls fn(chunk, begin, end) for every chunk [chunk·chunk_size, min(n, (chunk+1)·chunk_size))
/// of [0, n) on up to `threads` threads (serially for threads <= 1).
/// fn must not throw.
void parallel_for_chunks(std::size_t n, std::size_t chunk_size, int threads,
                         const std::function<void(std::size_t chunk, std::size_t begin,
                                                  std::size_t end)>& fn);

/// Calls `first` and `second`, two independent tasks that write nothing in common, side by
/// side: on up to two threads when `threads` > 1 (each task on one thread, so loops inside a task
/// run serially), else one after the other. Neither may throw.
void parallel_invoke(int threads, const std::function<void()>& first, const std::function<void()>& second);

/// Number of chunks of size `chunk_size` (> 0) covering [0, n).
inline std::size_t chunk_count(std::size_t n, std::size_t chunk_size) {
  return (n + chunk_size - 1) / chunk_size;
}

}  // namespace breastfit::spatial::detail
