// The heap settings: after keep_freed_heap_memory(), a block far above glibc's mapping threshold
// comes from the heap (no mapping of its own), once freed its memory serves the next one (the
// heap does not grow again), and a block that a thread allocates lies in the heap's part marked
// for transparent huge pages (the one heap every thread allocates from).
#include "breastfit/core/heap_reuse.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

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
  EXPECT_GE(with_a.arena, kBytes) << "the heap does not hold the block";
  EXPECT_GE(with_a.uordblks, before.uordblks + kBytes);
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

#if defined(__GLIBC__) && defined(__linux__) && defined(MADV_HUGEPAGE)
/// The VmFlags of the mapping of /proc/self/smaps that holds `address` ("" when none does).
std::string vm_flags_at(const void* address) {
  std::ifstream smaps("/proc/self/smaps");
  const auto p = reinterpret_cast<std::uintptr_t>(address);
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = lo <= p && p < hi;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return "";
}

TEST(HeapReuse, AThreadsLargeBlockLiesInTheHugePageHeap) {
  if (!std::ifstream("/proc/self/smaps")) GTEST_SKIP() << "no /proc/self/smaps";
  if (!std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled"))
    GTEST_SKIP() << "a kernel without transparent huge pages";
  ASSERT_TRUE(keep_freed_heap_memory());
  constexpr std::size_t kBytes = std::size_t{16} << 20;
  std::string flags;
  std::thread worker([&] {
    void* block = std::malloc(kBytes);
    ASSERT_NE(block, nullptr);
    // A byte in the block's middle: its whole 2 MiB pages are inside the marked part.
    flags = vm_flags_at(static_cast<unsigned char*>(block) + kBytes / 2);
    std::free(block);
  });
  worker.join();
  ASSERT_FALSE(flags.empty()) << "the block is in no mapping of /proc/self/smaps";
  EXPECT_NE(flags.find(" hg"), std::string::npos) << "not marked for huge pages: " << flags;
}
#endif

}  // namespace
}  // namespace breastfit
