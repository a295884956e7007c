#pragma once
/// \file The rows of a term with many residuals (one per correspondence) assembled on all cores:
/// the residuals are cut into chunks of a fixed size, each chunk goes into its own partial of the
/// normal equations (NormalEquations::partial) on some thread, and the chunks' costs and partials
/// are added in chunk order, so the result is the same bits whatever the number of threads.
#include <functional>

#include "breastfit/core/types.h"
#include "breastfit/fit/normal_equations.h"

namespace breastfit::fit {

/// The rows of residuals [begin, end) added to `eq` (nullptr: cost only); returns their cost.
using ChunkRows = std::function<double(Index begin, Index end, NormalEquations* eq)>;

/// Σ of rows(chunk) over the chunks of [0, n); with `eq`, their rows are added to it. Runs on
/// `threads` threads (≤ 0: all cores) when `eq` is given; the cost alone (cheap) runs on one, in
/// the same chunks.
double assemble_in_chunks(Index n, int threads, NormalEquations* eq, const ChunkRows& rows);

}  // namespace breastfit::fit
