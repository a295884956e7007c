#pragma once
/// \file Stable LSD radix sort of 64-bit keys carrying 32-bit values (private to the spatial
/// layer): the Morton-code sorts of the BVH build and of batched queries. With the values
/// 0, 1, 2, … on input the result equals std::sort on (key, value) pairs, i.e. ties by index.
#include <cstdint>
#include <vector>

namespace breastfit::spatial::detail {

/// Sorts `keys` ascending and applies the same permutation to `values` (same size), stably:
/// equal keys keep their input order. Only the low `key_bits` bits (1..64) are compared; the
/// higher bits must be zero. Digit passes whose digit is equal for all keys are skipped.
/// Linear time; uses one scratch copy of each array.
void radix_sort_pairs(std::vector<std::uint64_t>& keys, std::vector<std::uint32_t>& values,
                      int key_bits = 64);

}  // namespace breastfit::spatial::detail
