#include "breastfit/spatial/detail/radix_sort.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>

namespace breastfit::spatial::detail {
namespace {

/// 11-bit digits: 2048 counters per pass (8 KB, stays in L1).
constexpr int kDigitBits = 11;
constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;
constexpr std::uint64_t kDigitMask = kBuckets - 1;
using Histogram = std::array<std::uint32_t, kBuckets>;

/// Stable LSD passes over the 64-bit words `a` on the digits starting at bit `lo_bit`, for
/// `passes` digits (`tmp`: scratch of the same size). `count` holds each pass's digit
/// histogram; a pass whose digit is the same for all words is skipped.
void lsd_passes(std::vector<std::uint64_t>& a, std::vector<std::uint64_t>& tmp, int lo_bit,
                int passes, std::vector<Histogram>& count) {
  const std::size_t n = a.size();
  for (int p = 0; p < passes; ++p) {
    const int shift = lo_bit + p * kDigitBits;
    Histogram& c = count[p];
    if (c[(a[0] >> shift) & kDigitMask] == n) continue;  // same digit everywhere
    // Exclusive prefix sums: the first output slot of each digit.
    std::uint32_t sum = 0;
    for (std::uint32_t& x : c) {
      const std::uint32_t t = x;
      x = sum;
      sum += t;
    }
    const std::uint64_t* in = a.data();
    std::uint64_t* out = tmp.data();
    for (std::size_t i = 0; i < n; ++i) {  // in input order: stable
      const std::uint64_t w = in[i];
      out[c[(w >> shift) & kDigitMask]++] = w;
    }
    a.swap(tmp);
  }
}

}  // namespace

std::vector<std::uint32_t> radix_sort_order(std::vector<std::uint64_t>& keys, int key_bits) {
  const std::size_t n = keys.size();
  std::vector<std::uint32_t> order(n);
  if (n < 2) {
    if (n == 1) order[0] = 0;
    return order;
  }
  key_bits = std::clamp(key_bits, 1, 64);

  // Sort one 64-bit word per key: (the key's top <= 32 bits) << 32 | input position. The
  // radix passes run on the high half only, one 8-byte stream per pass (a 63-bit key: 3
  // passes instead of 6 over key and value arrays). Words with equal high halves keep their
  // input order; such runs (rare for Morton codes: cells of 2^-10.5 of the extent) are then
  // ordered by the full key, ties by position. The result is the stable sort by key.
  const int low_bits = std::max(0, key_bits - 32);  // key bits below the high half
  const int high_bits = key_bits - low_bits;
  const int passes = (high_bits + kDigitBits - 1) / kDigitBits;
  std::vector<Histogram> count(passes);
  for (Histogram& c : count) c.fill(0);
  std::vector<std::uint64_t> words(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t high = keys[i] >> low_bits;
    words[i] = high << 32 | static_cast<std::uint32_t>(i);
    for (int p = 0; p < passes; ++p) ++count[p][(high >> (p * kDigitBits)) & kDigitMask];
  }
  {
    std::vector<std::uint64_t> tmp(n);
    lsd_passes(words, tmp, 32, passes, count);
  }
  auto position = [](std::uint64_t w) { return static_cast<std::uint32_t>(w); };
  if (low_bits > 0) {
    auto by_key = [&](std::uint64_t a, std::uint64_t b) {
      const std::uint64_t ka = keys[position(a)], kb = keys[position(b)];
      return ka < kb || (ka == kb && position(a) < position(b));
    };
    for (std::size_t b = 0; b < n;) {
      std::size_t e = b + 1;
      while (e < n && (words[e] >> 32) == (words[b] >> 32)) ++e;
      if (e - b > 1) {
        if (e - b <= 16) {  // insertion sort: runs are short and mostly in order
          for (std::size_t i = b + 1; i < e; ++i) {
            const std::uint64_t w = words[i];
            std::size_t j = i;
            for (; j > b && by_key(w, words[j - 1]); --j) words[j] = words[j - 1];
            words[j] = w;
          }
        } else {
          std::sort(words.begin() + static_cast<std::ptrdiff_t>(b),
                    words.begin() + static_cast<std::ptrdiff_t>(e), by_key);
        }
      }
      b = e;
    }
  }
  std::vector<std::uint64_t> sorted_keys(n);
  for (std::size_t j = 0; j < n; ++j) {
    const std::uint32_t i = position(words[j]);
    sorted_keys[j] = keys[i];
    order[j] = i;
  }
  keys.swap(sorted_keys);
  return order;
}

}  // namespace breastfit::spatial::detail
