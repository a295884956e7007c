#include "breastfit/fit/parallel_chunks.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace breastfit::fit {
namespace {

TEST(ParallelChunks, ResolvesThreads) {
  EXPECT_EQ(resolve_threads(3), 3);
  EXPECT_GE(resolve_threads(0), 1);
  EXPECT_EQ(resolve_threads(-2), resolve_threads(0));
}

TEST(ParallelChunks, CountsChunks) {
  EXPECT_EQ(num_chunks(0, 64), 0);
  EXPECT_EQ(num_chunks(1, 64), 1);
  EXPECT_EQ(num_chunks(64, 64), 1);
  EXPECT_EQ(num_chunks(65, 64), 2);
}

TEST(ParallelChunks, VisitsEveryIndexOnceInFixedChunksWhateverTheThreads) {
  for (int threads : {1, 2, 4}) {
    const Index n = 1000, size = 64;
    std::vector<int> seen(n, 0);
    std::vector<std::pair<Index, Index>> bounds(num_chunks(n, size));
    for_each_chunk(n, size, threads, [&](Index c, Index begin, Index end) {
      bounds[c] = {begin, end};
      for (Index i = begin; i < end; ++i) ++seen[i];
    });
    for (Index i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << i;
    for (size_t c = 0; c < bounds.size(); ++c) {
      EXPECT_EQ(bounds[c].first, static_cast<Index>(c) * size);
      EXPECT_EQ(bounds[c].second, std::min(n, static_cast<Index>(c + 1) * size));
    }
  }
}

TEST(ParallelChunks, RethrowsTheLowestChunksExceptionAfterAllChunksRan) {
  for (int threads : {1, 2}) {
    std::vector<int> ran(10, 0);
    try {
      for_each_chunk(100, 10, threads, [&](Index c, Index, Index) {
        ran[c] = 1;
        if (c == 3 || c == 7) throw std::runtime_error("chunk " + std::to_string(c));
      });
      FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "chunk 3");
    }
    // With one thread the loop stops at the first failure; with more, every chunk runs.
    if (threads > 1)
      for (int r : ran) EXPECT_EQ(r, 1);
  }
}

TEST(ParallelChunks, EmptyRangeCallsNothing) {
  bool called = false;
  for_each_chunk(0, 16, 2, [&](Index, Index, Index) { called = true; });
  EXPECT_FALSE(called);
}

}  // namespace
}  // namespace breastfit::fit
