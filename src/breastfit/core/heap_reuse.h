#pragma once
/// \file Process-wide allocator setting for short-lived runs over large meshes: freed memory is
/// kept and reused instead of being returned to the system and faulted in (and zeroed by the
/// kernel) again. With glibc's defaults every block of 32 MB or more (a 3 M triangle scan's
/// index arrays, copies, sort buffers) is a fresh mapping, so a registration faults in about
/// 1.6 times its peak memory; docs/PERFORMANCE.md "Scaling".
#include <cstddef>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace breastfit {

/// Above this much free memory at the top of the heap, glibc gives it back to the system.
inline constexpr std::size_t kHeapTrimThresholdBytes = std::size_t{1} << 30;

/// Makes the main heap serve every allocation (no per-block mappings, which are unmapped on
/// free) and keeps up to kHeapTrimThresholdBytes of freed memory for reuse. Call once, early in
/// main(), before large allocations. Returns false where it has no effect (not glibc, or glibc
/// refused a setting). Only the speed and the peak memory change (by the heap's fragmentation,
/// about +10 % on a 3.8 M triangle registration), never a result.
inline bool keep_freed_heap_memory() {
#if defined(__GLIBC__)
  const bool mmap_off = mallopt(M_MMAP_MAX, 0) == 1;
  const bool trim_high = mallopt(M_TRIM_THRESHOLD, static_cast<int>(kHeapTrimThresholdBytes)) == 1;
  return mmap_off && trim_high;
#else
  return false;
#endif
}

}  // namespace breastfit
