#include "breastfit/spatial/detail/bvh4.h"

#include <cstddef>
#include <limits>

namespace breastfit::spatial::detail {
namespace {

/// A node whose four slots are empty (box +inf..-inf).
Bvh4Node empty_node() {
  Bvh4Node w;
  for (int s = 0; s < 4; ++s) {
    for (int k = 0; k < 3; ++k) {
      w.lo[k][s] = std::numeric_limits<float>::infinity();
      w.hi[k][s] = -std::numeric_limits<float>::infinity();
    }
    w.ref[s] = kBvh4Empty;
    w.count[s] = 0;
  }
  return w;
}

/// Fills slot `s` of `w` from binary node `n` (its box; ref and count set by the caller).
void set_box(Bvh4Node& w, int s, const BvhNode& n) {
  for (int k = 0; k < 3; ++k) {
    w.lo[k][s] = n.lo[k];
    w.hi[k][s] = n.hi[k];
  }
}

/// How many wide nodes emit() makes for binary inner node `b`.
std::size_t count_wide_nodes(const BvhNodes& binary, std::int32_t b) {
  std::size_t n = 1;
  const BvhNode& node = binary[static_cast<std::size_t>(b)];
  for (int c = 0; c < 2; ++c) {
    const BvhNode& child = binary[static_cast<std::size_t>(node.first + c)];
    if (child.is_leaf()) continue;
    for (int g = 0; g < 2; ++g) {
      if (!binary[static_cast<std::size_t>(child.first + g)].is_leaf())
        n += count_wide_nodes(binary, child.first + g);
    }
  }
  return n;
}

/// Appends the wide node for binary inner node `b` and, depth first, those of its inner
/// grandchildren; returns its index.
std::int32_t emit(const BvhNodes& binary, std::int32_t b, Bvh4Nodes& out) {
  const auto self = static_cast<std::int32_t>(out.size());
  out.push_back(empty_node());
  // Children: the binary children, an inner one replaced by its two children.
  std::int32_t kids[4];
  int n = 0;
  const BvhNode& node = binary[static_cast<std::size_t>(b)];
  for (int c = 0; c < 2; ++c) {
    const std::int32_t ci = node.first + c;
    const BvhNode& child = binary[static_cast<std::size_t>(ci)];
    if (child.is_leaf()) {
      kids[n++] = ci;
    } else {
      kids[n++] = child.first;
      kids[n++] = child.first + 1;
    }
  }
  for (int s = 0; s < n; ++s) {
    const BvhNode& k = binary[static_cast<std::size_t>(kids[s])];
    std::int32_t ref, count = 0;
    if (k.is_leaf()) {
      ref = ~k.first;
      count = k.count;
    } else {
      ref = emit(binary, kids[s], out);  // may reallocate `out`
    }
    Bvh4Node& w = out[static_cast<std::size_t>(self)];
    set_box(w, s, k);
    w.ref[s] = ref;
    w.count[s] = count;
  }
  return self;
}

}  // namespace

Bvh4Nodes collapse_to_bvh4(const BvhNodes& binary) {
  Bvh4Nodes out;
  if (binary.empty()) return out;
  if (binary[0].is_leaf()) {
    Bvh4Node w = empty_node();
    set_box(w, 0, binary[0]);
    w.ref[0] = ~binary[0].first;
    w.count[0] = binary[0].count;
    out.push_back(w);
    return out;
  }
  out.reserve(count_wide_nodes(binary, 0));  // exactly: no reallocation, no slack
  emit(binary, 0, out);
  return out;
}

}  // namespace breastfit::spatial::detail
