#include "breastfit/spatial/detail/radix_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "breastfit/core/rng.h"

namespace breastfit::spatial::detail {
namespace {

/// The reference: std::stable_sort of (key, value) by key.
void reference_sort(std::vector<std::uint64_t>& keys, std::vector<std::uint32_t>& values) {
  std::vector<std::size_t> order(keys.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
  std::vector<std::uint64_t> k(keys.size());
  std::vector<std::uint32_t> v(keys.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    k[i] = keys[order[i]];
    v[i] = values[order[i]];
  }
  keys.swap(k);
  values.swap(v);
}

void expect_same_as_reference(std::vector<std::uint64_t> keys, int key_bits) {
  Rng rng(keys.size() + 17);
  std::vector<std::uint32_t> values(keys.size());
  // Arbitrary values (not 0..n-1): the sort must carry them, not recompute them.
  for (auto& v : values) v = static_cast<std::uint32_t>(rng.below(1u << 30));
  std::vector<std::uint64_t> ref_keys = keys;
  std::vector<std::uint32_t> ref_values = values;
  reference_sort(ref_keys, ref_values);
  radix_sort_pairs(keys, values, key_bits);
  ASSERT_EQ(keys, ref_keys);
  ASSERT_EQ(values, ref_values);
}

std::uint64_t random_bits(Rng& rng, int bits) {
  const std::uint64_t x = rng.next_u64();
  return bits >= 64 ? x : x & ((std::uint64_t{1} << bits) - 1);
}

TEST(RadixSortPairs, EmptyAndSingle) {
  expect_same_as_reference({}, 63);
  expect_same_as_reference({42}, 63);
}

TEST(RadixSortPairs, MatchesStableSortForAllKeyWidths) {
  Rng rng(1);
  for (const int bits : {1, 8, 11, 21, 32, 33, 43, 63, 64}) {
    for (const std::size_t n : {2u, 3u, 17u, 1000u, 40000u}) {
      std::vector<std::uint64_t> keys(n);
      for (auto& k : keys) k = random_bits(rng, bits);
      expect_same_as_reference(keys, bits);
    }
  }
}

TEST(RadixSortPairs, ManyDuplicatesKeepInputOrder) {
  Rng rng(2);
  std::vector<std::uint64_t> keys(20000);
  for (auto& k : keys) k = rng.below(7) << 40 | rng.below(3);  // 21 distinct keys
  expect_same_as_reference(keys, 63);
}

TEST(RadixSortPairs, LongRunsSharingTheHigh32Bits) {
  // All keys agree above bit 31 and differ below: the runs are ordered by the low bits
  // (short runs by insertion, long ones by std::sort).
  Rng rng(3);
  for (const std::size_t run : {2u, 16u, 17u, 5000u}) {
    std::vector<std::uint64_t> keys;
    for (std::size_t i = 0; i < 20000; ++i) {
      const std::uint64_t high = (i / run) * 0x9e3779b1ULL % (1u << 31);
      keys.push_back(high << 31 | rng.below(std::uint64_t{1} << 31));
    }
    expect_same_as_reference(keys, 63);
  }
}

TEST(RadixSortPairs, AlreadySortedAndReversed) {
  std::vector<std::uint64_t> keys(5000);
  for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = i * 0x10000000001ULL;
  expect_same_as_reference(keys, 63);
  std::reverse(keys.begin(), keys.end());
  expect_same_as_reference(keys, 63);
}

}  // namespace
}  // namespace breastfit::spatial::detail
