// The four-wide tree of the closest-point index: collapsing a binary tree keeps every leaf once
// with its box, every inner node's grandchildren in order, and nothing else.
#include "breastfit/spatial/detail/bvh4.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "breastfit/spatial/detail/triangle_tables.h"
#include "spatial/spatial_test_meshes.h"

namespace breastfit::spatial::detail {
namespace {

namespace meshes = breastfit::test::spatial_meshes;

void expect_box(const Bvh4Node& w, int s, const BvhNode& n) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(w.lo[k][s], n.lo[k]);
    EXPECT_EQ(w.hi[k][s], n.hi[k]);
  }
}

/// Walks the wide tree from `w` alongside binary inner node `b`, checking the slots and
/// counting the leaves reached (by their `first`).
void check_node(const Bvh4Nodes& wide, std::int32_t w, const BvhNodes& binary, std::int32_t b,
                std::map<std::int32_t, int>& leaves) {
  const Bvh4Node& node = wide[static_cast<std::size_t>(w)];
  std::vector<std::int32_t> expected;
  const BvhNode& bn = binary[static_cast<std::size_t>(b)];
  for (int c = 0; c < 2; ++c) {
    const BvhNode& child = binary[static_cast<std::size_t>(bn.first + c)];
    if (child.is_leaf()) {
      expected.push_back(bn.first + c);
    } else {
      expected.push_back(child.first);
      expected.push_back(child.first + 1);
    }
  }
  for (int s = 0; s < 4; ++s) {
    if (s >= static_cast<int>(expected.size())) {
      EXPECT_EQ(node.ref[s], kBvh4Empty);
      continue;
    }
    const BvhNode& child = binary[static_cast<std::size_t>(expected[static_cast<std::size_t>(s)])];
    expect_box(node, s, child);
    if (child.is_leaf()) {
      ASSERT_LT(node.ref[s], 0);
      EXPECT_EQ(~node.ref[s], child.first);
      EXPECT_EQ(node.count[s], child.count);
      ++leaves[child.first];
    } else {
      ASSERT_GT(node.ref[s], w);  // pre-order: children after their parent
      ASSERT_LT(node.ref[s], static_cast<std::int32_t>(wide.size()));
      check_node(wide, node.ref[s], binary, expected[static_cast<std::size_t>(s)], leaves);
    }
  }
}

TEST(Bvh4, CollapseKeepsEveryLeafOnceWithItsBox) {
  for (const int n : {5, 17, 300, 5000}) {
    SCOPED_TRACE(n);
    const TriangleMesh m = meshes::random_soup(n, 100.0, 4.0, 7 + static_cast<std::uint64_t>(n));
    const Bvh bvh = Bvh::build(triangle_boxes(m));
    const Bvh4Nodes wide = collapse_to_bvh4(bvh.nodes);
    std::map<std::int32_t, int> leaves;
    ASSERT_FALSE(bvh.nodes[0].is_leaf());
    check_node(wide, 0, bvh.nodes, 0, leaves);
    int binary_leaves = 0;
    for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
      if (i == 1 || !bvh.nodes[i].is_leaf()) continue;
      ++binary_leaves;
      EXPECT_EQ(leaves[bvh.nodes[i].first], 1) << "leaf " << i;
    }
    EXPECT_EQ(static_cast<int>(leaves.size()), binary_leaves);
  }
}

TEST(Bvh4, SingleLeafAndEmptyTrees) {
  const TriangleMesh m = meshes::random_soup(3, 10.0, 2.0, 3);
  const Bvh bvh = Bvh::build(triangle_boxes(m));
  ASSERT_TRUE(bvh.nodes[0].is_leaf());
  const Bvh4Nodes wide = collapse_to_bvh4(bvh.nodes);
  ASSERT_EQ(wide.size(), 1u);
  EXPECT_EQ(~wide[0].ref[0], bvh.nodes[0].first);
  EXPECT_EQ(wide[0].count[0], bvh.nodes[0].count);
  expect_box(wide[0], 0, bvh.nodes[0]);
  for (int s = 1; s < 4; ++s) EXPECT_EQ(wide[0].ref[s], kBvh4Empty);
  EXPECT_TRUE(collapse_to_bvh4(BvhNodes()).empty());
}

}  // namespace
}  // namespace breastfit::spatial::detail
