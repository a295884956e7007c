// The coarse depth test: a box is hidden only behind the farthest depth over all its blocks.
#include "breastfit/render/detail/block_far.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <limits>
#include <vector>

namespace breastfit::render::detail {
namespace {

TEST(BlockFar, HidesOnlyBehindTheFarthestDepthOfEveryBlock) {
  const int w = 20, h = 12;  // blocks of 8: 3 × 2, the last ones partial
  std::vector<float> depth(static_cast<size_t>(w) * h, 5.0f);
  depth[static_cast<size_t>(3) * w + 4] = 9.0f;                                // block (0, 0)
  depth[static_cast<size_t>(10) * w + 17] = std::numeric_limits<float>::infinity();  // block (2, 1): empty
  BlockFar far(w, h);
  far.fill([&](size_t p) { return depth[p]; });
  EXPECT_TRUE(far.hidden(8, 0, 15, 7, 5.0));   // block (1, 0): farthest 5
  EXPECT_FALSE(far.hidden(8, 0, 15, 7, 4.9));
  EXPECT_FALSE(far.hidden(0, 0, 15, 7, 5.0));  // block (0, 0) reaches 9
  EXPECT_TRUE(far.hidden(0, 0, 15, 7, 9.0));
  EXPECT_TRUE(far.hidden(9, 9, 15, 11, 6.0));   // block (1, 1)
  EXPECT_FALSE(far.hidden(9, 9, 16, 11, 1e30));  // block (2, 1) has an empty pixel: never hidden
}

TEST(BlockFar, RefillsFromNewDepths) {
  BlockFar far(8, 8);
  far.fill([](size_t) { return 1.0f; });
  EXPECT_TRUE(far.hidden(0, 0, 7, 7, 2.0));
  far.fill([](size_t p) { return p == 63 ? 3.0f : 1.0f; });
  EXPECT_FALSE(far.hidden(0, 0, 7, 7, 2.0));
}

}  // namespace
}  // namespace breastfit::render::detail
