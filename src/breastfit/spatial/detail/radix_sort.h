#pragma once
/// \file Stable LSD radix sort of 64-bit keys returning their order (private to the spatial
/// layer): the Morton-code sorts of the BVH build and of batched queries. The order equals
/// std::sort on (key, input position) pairs, i.e. ties by index.
#include <cstdint>
#include <vector>

namespace breastfit::spatial::detail {

/// Sorts `keys` ascending, stably (equal keys keep their input order), and returns the input
/// position of each sorted key (every caller sorts the positions 0, 1, 2, … along: returning
/// them saves carrying and gathering a value array). Only the low `key_bits` bits (1..64) are
/// compared; the higher bits must be zero. Digit passes whose digit is equal for all keys are
/// skipped. Linear time; uses one scratch copy of the keys.
std::vector<std::uint32_t> radix_sort_order(std::vector<std::uint64_t>& keys, int key_bits = 64);

}  // namespace breastfit::spatial::detail
