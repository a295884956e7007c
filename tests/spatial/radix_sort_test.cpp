#include "breastfit/spatial/detail/radix_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "breastfit/core/rng.h"

namespace breastfit::spatial::detail {
namespace {

/// The reference: the input positions ordered by std::stable_sort on the key.
std::vector<std::uint32_t> reference_order(const std::vector<std::uint64_t>& keys) {
  std::vector<std::uint32_t> order(keys.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  return order;
}

void expect_same_as_reference(std::vector<std::uint64_t> keys, int key_bits) {
  const std::vector<std::uint32_t> ref_order = reference_order(keys);
  std::vector<std::uint64_t> ref_keys(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) ref_keys[i] = keys[ref_order[i]];
  const std::vector<std::uint32_t> order = radix_sort_order(keys, key_bits);
  ASSERT_EQ(keys, ref_keys);
  ASSERT_EQ(order, ref_order);
}

std::uint64_t random_bits(Rng& rng, int bits) {
  const std::uint64_t x = rng.next_u64();
  return bits >= 64 ? x : x & ((std::uint64_t{1} << bits) - 1);
}

TEST(RadixSortOrder, EmptyAndSingle) {
  expect_same_as_reference({}, 63);
  expect_same_as_reference({42}, 63);
}

TEST(RadixSortOrder, MatchesStableSortForAllKeyWidths) {
  Rng rng(1);
  for (const int bits : {1, 8, 11, 21, 32, 33, 43, 63, 64}) {
    for (const std::size_t n : {2u, 3u, 17u, 1000u, 40000u}) {
      std::vector<std::uint64_t> keys(n);
      for (auto& k : keys) k = random_bits(rng, bits);
      expect_same_as_reference(keys, bits);
    }
  }
}

TEST(RadixSortOrder, ManyDuplicatesKeepInputOrder) {
  Rng rng(2);
  std::vector<std::uint64_t> keys(20000);
  for (auto& k : keys) k = rng.below(7) << 40 | rng.below(3);  // 21 distinct keys
  expect_same_as_reference(keys, 63);
}

TEST(RadixSortOrder, LongRunsSharingTheHigh32Bits) {
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

TEST(RadixSortOrder, AlreadySortedAndReversed) {
  std::vector<std::uint64_t> keys(5000);
  for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = i * 0x10000000001ULL;
  expect_same_as_reference(keys, 63);
  std::reverse(keys.begin(), keys.end());
  expect_same_as_reference(keys, 63);
}

}  // namespace
}  // namespace breastfit::spatial::detail
