#include "breastfit/fit/chunked_assembly.h"

#include <vector>

#include "breastfit/fit/parallel_chunks.h"

namespace breastfit::fit {
namespace {

// Residuals per chunk: large enough that zeroing and adding a chunk's partial H (149² for the
// default template) stays small against its rows' rank updates.
constexpr Index kRowChunk = 256;

}  // namespace

double assemble_in_chunks(Index n, int threads, NormalEquations* eq, const ChunkRows& rows) {
  const Index chunks = num_chunks(n, kRowChunk);
  std::vector<NormalEquations*> parts(static_cast<size_t>(chunks), nullptr);
  if (eq)
    for (Index c = 0; c < chunks; ++c) parts[static_cast<size_t>(c)] = &eq->partial(static_cast<int>(c));
  std::vector<double> costs(static_cast<size_t>(chunks), 0.0);
  for_each_chunk(n, kRowChunk, eq ? threads : 1, [&](Index c, Index begin, Index end) {
    costs[static_cast<size_t>(c)] = rows(begin, end, parts[static_cast<size_t>(c)]);
  });
  double cost = 0.0;
  for (Index c = 0; c < chunks; ++c) {
    cost += costs[static_cast<size_t>(c)];
    if (eq) eq->add_partial(*parts[static_cast<size_t>(c)]);
  }
  return cost;
}

}  // namespace breastfit::fit
