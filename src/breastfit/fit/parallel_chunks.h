#pragma once
/// \file Deterministic parallel loops of the fit layer (the process's worker pool,
/// core/chunk_pool.h). A range [0, n) is cut into chunks
/// of a fixed size that does not depend on the number of threads; the chunks run on up to
/// `threads` threads and the callers combine the chunks' results in chunk order. So every sum is
/// taken in the same order, and the results are the same bits whatever the thread count.
#include <functional>

#include "breastfit/core/types.h"

namespace breastfit::fit {

/// The threads to use for `requested`: itself when > 0. Otherwise (0: "all cores") OMP_NUM_THREADS
/// when set, else the cores not already busy: the processors minus the whole part of the 1-minute
/// load average, at least 1 (on a machine whose cores are all taken by other work, threads that
/// wait for each other at every loop's end are slower than one).
int resolve_threads(int requested);

/// Number of chunks of size `chunk_size` (> 0) covering [0, n).
Index num_chunks(Index n, Index chunk_size);

/// Calls fn(chunk, begin, end) once for every chunk [chunk·chunk_size, min(n, (chunk+1)·chunk_size))
/// of [0, n), on up to resolve_threads(threads) threads: concurrently and in any order, so fn
/// writes only to the chunk's own slots. When fn throws, the exception of the lowest chunk is
/// rethrown once every chunk has run.
void for_each_chunk(Index n, Index chunk_size, int threads,
                    const std::function<void(Index chunk, Index begin, Index end)>& fn);

}  // namespace breastfit::fit
