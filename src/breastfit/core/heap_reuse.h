#pragma once
/// \file Process-wide allocator settings for short-lived runs over large meshes: freed memory is
/// kept and reused instead of being returned to the system and faulted in (and zeroed by the
/// kernel) again, and the heap's first growth is backed by transparent huge pages. With glibc's
/// defaults every block of 32 MB or more (a 3 M triangle scan's index arrays, copies, sort
/// buffers) is a fresh mapping, so a registration faults in about 1.6 times its peak memory; and
/// every 4 KiB page touched for the first time is a page fault of its own, which under some
/// hypervisors costs ~10 µs: a third of a registration's CPU time. docs/PERFORMANCE.md "Scaling"
/// and "Page faults".
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace breastfit {

/// Above this much free memory at the top of the heap, glibc gives it back to the system.
inline constexpr std::size_t kHeapTrimThresholdBytes = (std::size_t{1} << 31) - 1;  // mallopt takes an int

/// How much of the heap's address space keep_freed_heap_memory() reserves up front and marks for
/// transparent huge pages: address space only; memory is taken when first touched, 2 MiB at a
/// time.
inline constexpr std::size_t kHugePageHeapBytes = std::size_t{7} << 28;  // 1.75 GiB
static_assert(kHugePageHeapBytes < kHeapTrimThresholdBytes, "the reserved block must stay in the heap when freed");

/// The size of a transparent huge page on x86-64 and arm64 (4 KiB base pages).
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

/// Makes the heap serve every allocation of every thread (no per-block mappings, which are
/// unmapped on free; no per-thread arenas), keeps up to kHeapTrimThresholdBytes of freed memory
/// for reuse, and grows the heap once by kHugePageHeapBytes marked for transparent huge pages
/// (madvise MADV_HUGEPAGE; where the system allows them, a first touch faults in 2 MiB instead of
/// 4 KiB). Call once, early in main(), before large allocations and before any thread starts.
/// Returns false where it has no effect (not glibc, or glibc refused a setting); the huge pages
/// are best effort (a kernel without them, or one that refuses, changes nothing). Only the speed
/// and the peak memory change, never a result.
inline bool keep_freed_heap_memory() {
#if defined(__GLIBC__)
  const bool mmap_off = mallopt(M_MMAP_MAX, 0) == 1;
  const bool trim_high = mallopt(M_TRIM_THRESHOLD, static_cast<int>(kHeapTrimThresholdBytes)) == 1;
  const bool one_arena = mallopt(M_ARENA_MAX, 1) == 1;  // threads' blocks from the same heap
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Grow the heap once (address space: nothing is touched), mark its whole 2 MiB pages for huge
  // pages, and give the block back: it stays in the heap (below the trim threshold) and serves
  // the blocks that follow.
  if (void* block = std::malloc(kHugePageHeapBytes)) {
    const auto begin = reinterpret_cast<std::uintptr_t>(block);
    const std::uintptr_t lo = (begin + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    const std::uintptr_t hi = (begin + kHugePageHeapBytes) / kHugePageBytes * kHugePageBytes;
    if (hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
    std::free(block);
  }
#endif
  return mmap_off && trim_high && one_arena;
#else
  return false;
#endif
}

}  // namespace breastfit
