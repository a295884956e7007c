#include "breastfit/core/chunk_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace breastfit {
namespace {

TEST(ChunkPool, CountsTheProcessors) { EXPECT_GE(available_processors(), 1); }

TEST(ChunkPool, EveryChunkRunsOnceWhateverTheThreads) {
  for (int threads : {0, 1, 2, 3, 8}) {
    std::vector<std::atomic<int>> runs(101);
    run_chunks(runs.size(), threads, [&](std::size_t c) { ++runs[c]; });
    for (std::size_t c = 0; c < runs.size(); ++c) EXPECT_EQ(runs[c].load(), 1) << "chunk " << c << ", " << threads << " threads";
  }
  run_chunks(0, 2, [](std::size_t) { FAIL() << "no chunk to run"; });
}

TEST(ChunkPool, ManyShortLoopsInARowLoseNoChunk) {
  // The fit's pattern: hundreds of small loops with little serial work between them, so workers
  // wake, spin and sleep across loops; every loop must see each of its chunks exactly once.
  std::vector<int> out(16);
  for (int loop = 0; loop < 3000; ++loop) {
    run_chunks(out.size(), 2 + loop % 3, [&](std::size_t c) { out[c] = loop + static_cast<int>(c); });
    for (std::size_t c = 0; c < out.size(); ++c) ASSERT_EQ(out[c], loop + static_cast<int>(c)) << "loop " << loop;
  }
}

TEST(ChunkPool, UsesOtherThreadsWhenAsked) {
  std::mutex mutex;
  std::set<std::thread::id> ids;
  // Chunks slow enough that a woken worker takes some before the caller has run them all.
  run_chunks(64, 2, [&](std::size_t) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::lock_guard lock(mutex);
    ids.insert(std::this_thread::get_id());
  });
  EXPECT_EQ(ids.size(), 2u);
  ids.clear();
  run_chunks(8, 1, [&](std::size_t) { ids.insert(std::this_thread::get_id()); });
  EXPECT_EQ(ids, std::set<std::thread::id>{std::this_thread::get_id()});
}

TEST(ChunkPool, ALoopInsideAChunkRunsOnItsThread) {
  std::vector<std::atomic<int>> runs(8 * 8);
  run_chunks(8, 2, [&](std::size_t outer) {
    const auto id = std::this_thread::get_id();
    run_chunks(8, 2, [&](std::size_t inner) {
      EXPECT_EQ(std::this_thread::get_id(), id);
      ++runs[outer * 8 + inner];
    });
  });
  for (const auto& r : runs) EXPECT_EQ(r.load(), 1);
}

TEST(ChunkPool, TheLowestFailingChunkIsRethrownAfterAllRan) {
  for (int threads : {1, 2, 3}) {
    std::vector<std::atomic<int>> ran(10);
    try {
      run_chunks(ran.size(), threads, [&](std::size_t c) {
        ++ran[c];
        if (c == 3 || c == 7) throw std::runtime_error("chunk " + std::to_string(c));
      });
      ADD_FAILURE() << "nothing thrown";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "chunk 3");
    }
    // One thread stops at the first failure; several run every chunk.
    for (std::size_t c = 0; c < ran.size(); ++c) EXPECT_EQ(ran[c].load(), threads > 1 || c <= 3 ? 1 : 0) << c;
  }
}

}  // namespace
}  // namespace breastfit
