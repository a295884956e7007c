// The heap setting: after keep_freed_heap_memory(), a block far above glibc's mapping threshold
// comes from the heap (no mapping of its own), and once freed its memory serves the next one
// (the heap does not grow again).
#include "breastfit/core/heap_reuse.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

namespace breastfit {
namespace {

#if defined(__GLIBC__)
TEST(HeapReuse, LargeBlocksComeFromTheHeapAndAreReused) {
  ASSERT_TRUE(keep_freed_heap_memory());
  constexpr std::size_t kBytes = std::size_t{64} << 20;  // above glibc's largest mmap threshold
  const struct mallinfo2 before = mallinfo2();
  auto* a = static_cast<unsigned char*>(std::malloc(kBytes));
  ASSERT_NE(a, nullptr);
  std::memset(a, 1, kBytes);
  const struct mallinfo2 with_a = mallinfo2();
  EXPECT_EQ(with_a.hblkhd, before.hblkhd) << "the block was mapped on its own";
  EXPECT_GE(with_a.arena, before.arena + kBytes);
  std::free(a);
  const struct mallinfo2 freed = mallinfo2();
  EXPECT_EQ(freed.arena, with_a.arena) << "the freed memory went back to the system";
  auto* b = static_cast<unsigned char*>(std::malloc(kBytes));
  ASSERT_NE(b, nullptr);
  std::memset(b, 2, kBytes);
  EXPECT_EQ(mallinfo2().arena, with_a.arena) << "the second block did not reuse the first's memory";
  std::free(b);
}
#else
TEST(HeapReuse, NoEffectWithoutGlibc) { EXPECT_FALSE(keep_freed_heap_memory()); }
#endif

}  // namespace
}  // namespace breastfit
