#include "breastfit/core/task_queue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

namespace breastfit {
namespace {

TEST(TaskQueue, EveryTaskRunsOnceWhateverTheWorkers) {
  for (unsigned workers : {0u, 1u, 2u, 4u, 100u}) {
    std::vector<std::atomic<int>> runs(37);
    run_in_order(runs.size(), workers, [&](std::size_t i) { ++runs[i]; });
    for (std::size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i].load(), 1) << "task " << i << ", " << workers << " workers";
  }
  run_in_order(0, 2, [](std::size_t) { FAIL() << "no task to run"; });
}

TEST(TaskQueue, TheFirstFailingTaskInOrderIsRethrownAfterAllRan) {
  for (unsigned workers : {1u, 3u}) {
    std::atomic<int> ran{0};
    try {
      run_in_order(10, workers, [&](std::size_t i) {
        ++ran;
        if (i == 7 || i == 4) throw std::runtime_error("task " + std::to_string(i));
      });
      ADD_FAILURE() << "nothing thrown";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "task 4");
    }
    EXPECT_EQ(ran.load(), 10) << workers << " workers";
  }
}

}  // namespace
}  // namespace breastfit
