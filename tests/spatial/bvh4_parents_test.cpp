// Where the faces and nodes of the closest-point index's four-wide tree hang: every face's leaf
// is a slot of the node named for it, every node a child of its parent, the root has none.
#include "breastfit/spatial/detail/bvh4_parents.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "breastfit/spatial/detail/triangle_tables.h"
#include "spatial/spatial_test_meshes.h"

namespace breastfit::spatial::detail {
namespace {

namespace meshes = breastfit::test::spatial_meshes;

struct Wide {
  Bvh4Nodes nodes;
  LeafBlocks blocks;
};

/// The tree as ClosestPointIndex builds it (an LBVH, its leaf blocks, collapsed four-wide).
Wide wide_tree(const TriangleMesh& m) {
  MortonSorted sorted = triangle_morton_order(m);
  BvhNodes binary;
  build_morton_topology(sorted.codes, kMaxLeafSize, binary);
  Wide w;
  w.blocks = build_leaf_blocks(m, triangle_flags(m, nullptr), sorted.prims, binary, 1);
  fit_inner_boxes(binary);
  w.nodes = collapse_to_bvh4(binary);
  return w;
}

/// Whether `node`'s slots hold a leaf whose block lists `face`.
bool holds_face(const Wide& w, std::int32_t node, Index face) {
  const Bvh4Node& n = w.nodes[static_cast<std::size_t>(node)];
  for (int s = 0; s < 4 && n.ref[s] != kBvh4Empty; ++s) {
    if (n.ref[s] >= 0) continue;
    const auto* h = reinterpret_cast<const LeafHeader*>(w.blocks[static_cast<std::size_t>(~n.ref[s])].bytes);
    for (int t = 0; t < h->count; ++t)
      if (h->face[t] == face) return true;
  }
  return false;
}

TEST(Bvh4Parents, EveryFaceAndNodeHangsWhereTheTreeHoldsIt) {
  for (const auto& [name, m] : {std::pair<std::string, TriangleMesh>{"sheet", meshes::noisy_sheet(40, 2.5, 0.8, 0.15, 4)},
                                {"soup", meshes::random_soup(3000, 100.0, 5.0, 2)}}) {
    SCOPED_TRACE(name);
    const Wide w = wide_tree(m);
    ASSERT_GT(w.nodes.size(), 100u);
    const Bvh4Parents p = bvh4_parents(w.nodes, w.blocks, m.num_faces());
    ASSERT_EQ(p.node_parent.size(), w.nodes.size());
    ASSERT_EQ(p.face_node.size(), static_cast<std::size_t>(m.num_faces()));
    EXPECT_EQ(p.node_parent[0], -1);
    for (std::size_t n = 1; n < w.nodes.size(); ++n) {
      const std::int32_t up = p.node_parent[n];
      ASSERT_GE(up, 0) << "node " << n;
      ASSERT_LT(up, static_cast<std::int32_t>(n));  // pre-order: parents first
      const Bvh4Node& parent = w.nodes[static_cast<std::size_t>(up)];
      int slots = 0;
      for (int s = 0; s < 4; ++s) slots += parent.ref[s] == static_cast<std::int32_t>(n);
      EXPECT_EQ(slots, 1) << "node " << n;
    }
    for (Index f = 0; f < m.num_faces(); ++f) {
      const std::int32_t node = p.face_node[static_cast<std::size_t>(f)];
      ASSERT_GE(node, 0) << "face " << f;
      EXPECT_TRUE(holds_face(w, node, f)) << "face " << f;
    }
  }
}

TEST(Bvh4Parents, ASingleLeafHangsFromTheRoot) {
  const TriangleMesh m = meshes::make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, 1.0 / 3}},
                                           {{0, 1, 2}, {1, 3, 2}});
  const Wide w = wide_tree(m);
  ASSERT_EQ(w.nodes.size(), 1u);
  const Bvh4Parents p = bvh4_parents(w.nodes, w.blocks, m.num_faces());
  EXPECT_EQ(p.node_parent, std::vector<std::int32_t>{-1});
  EXPECT_EQ(p.face_node, (std::vector<std::int32_t>{0, 0}));
}

}  // namespace
}  // namespace breastfit::spatial::detail
