#include "breastfit/spatial/detail/parallel_for.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

namespace breastfit::spatial::detail {
namespace {

TEST(ParallelForChunks, EveryIndexOnceInItsFixedChunk) {
  for (const std::size_t n : {0u, 1u, 7u, 64u, 65u, 1000u}) {
    for (const int threads : {0, 1, 2, 3, 8}) {
      std::vector<int> visits(n, 0);
      std::vector<std::size_t> chunk_of(n, 999);
      parallel_for_chunks(n, 16, threads, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        EXPECT_EQ(begin, 16 * chunk);
        EXPECT_LE(end, n);
        EXPECT_LT(begin, end);
        for (std::size_t i = begin; i < end; ++i) {
          ++visits[i];
          chunk_of[i] = chunk;
        }
      });
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(visits[i], 1) << "index " << i << ", " << threads << " threads";
        ASSERT_EQ(chunk_of[i], i / 16);
      }
    }
  }
  EXPECT_EQ(chunk_count(0, 16), 0u);
  EXPECT_EQ(chunk_count(16, 16), 1u);
  EXPECT_EQ(chunk_count(17, 16), 2u);
}

TEST(ParallelInvoke, EachTaskOnceInOrderOnOneThread) {
  for (const int threads : {0, 1, 2, 3}) {
    std::vector<int> order;
    int first = 0, second = 0;
    parallel_invoke(
        threads,
        [&] {
          ++first;
          if (threads <= 1) order.push_back(1);
        },
        [&] {
          ++second;
          if (threads <= 1) order.push_back(2);
        });
    EXPECT_EQ(first, 1) << threads << " threads";
    EXPECT_EQ(second, 1) << threads << " threads";
    if (threads <= 1) EXPECT_EQ(order, (std::vector<int>{1, 2}));
  }
}

}  // namespace
}  // namespace breastfit::spatial::detail
