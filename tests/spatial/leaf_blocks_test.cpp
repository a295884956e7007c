#include "breastfit/spatial/detail/leaf_blocks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "breastfit/spatial/detail/triangle_tables.h"
#include "spatial/spatial_test_meshes.h"

namespace breastfit::spatial::detail {
namespace {

namespace meshes = breastfit::test::spatial_meshes;

/// A sheet with holes and an open border, made irregular: every 13th face degenerate (a
/// repeated corner), every 29th a single point, the vertices of one half rounded to floats
/// (leaves of both kinds side by side) and a few vertices no face uses.
TriangleMesh irregular_mesh(int n) {
  TriangleMesh m = meshes::noisy_sheet(n, 1.0, 0.4, 0.05, 77);
  for (Index f = 0; f < m.num_faces(); f += 13) m.F(f, 2) = m.F(f, 1);
  for (Index f = 5; f < m.num_faces(); f += 29) m.F(f, 1) = m.F(f, 2) = m.F(f, 0);
  const double mid = 0.5 * (m.V.col(0).minCoeff() + m.V.col(0).maxCoeff());
  for (Index v = 0; v < m.num_vertices(); ++v)
    if (m.V(v, 0) < mid) m.V.row(v) = m.V.row(v).cast<float>().cast<double>();
  const Index nv = m.num_vertices();
  m.V.conservativeResize(nv + 3, 3);
  m.V.bottomRows(3).setConstant(1e6);
  return m;
}

struct Tree {
  std::vector<std::uint32_t> prims;
  BvhNodes nodes;
};

Tree lbvh(const TriangleMesh& m) {
  MortonSorted sorted = triangle_morton_order(m);
  Tree t;
  build_morton_topology(sorted.codes, kMaxLeafSize, t.nodes);
  t.prims = std::move(sorted.prims);
  return t;
}

bool is_float(double x) { return static_cast<double>(static_cast<float>(x)) == x; }

TEST(LeafBlocks, EachBlockHoldsItsLeafsTrianglesAndDistinctCorners) {
  const TriangleMesh m = irregular_mesh(60);
  const std::vector<std::uint8_t> flags = triangle_flags(m, nullptr);
  Tree t = lbvh(m);
  const BvhNodes slots = t.nodes;  // the leaves' slot ranges before the build
  const LeafBlocks blocks = build_leaf_blocks(m, flags, t.prims, t.nodes, 1);
  std::size_t next_line = 0;
  int float_leaves = 0, double_leaves = 0, shared_corners = 0;
  for (std::size_t i = 0; i < t.nodes.size(); ++i) {
    if (i == 1 || !slots[i].is_leaf()) continue;
    SCOPED_TRACE("node " + std::to_string(i));
    const BvhNode& n = t.nodes[i];
    ASSERT_EQ(static_cast<std::size_t>(n.first), next_line);  // in node order, back to back
    const unsigned char* base = blocks[static_cast<std::size_t>(n.first)].bytes;
    LeafHeader h;
    std::memcpy(&h, base, sizeof h);
    ASSERT_EQ(h.count, slots[i].count);
    // The corners: each triangle's vertices in first-use order, each once.
    std::vector<Index> corners;
    bool exact = true;
    for (int tri = 0; tri < h.count; ++tri) {
      const auto f = static_cast<Index>(t.prims[static_cast<std::size_t>(slots[i].first + tri)]);
      EXPECT_EQ(h.face[tri], f);
      EXPECT_EQ(h.flags[tri], flags[static_cast<std::size_t>(f)]);
      for (int k = 0; k < 3; ++k) {
        const Index v = m.F(f, k);
        const auto slot = std::find(corners.begin(), corners.end(), v) - corners.begin();
        if (slot == static_cast<std::ptrdiff_t>(corners.size())) {
          corners.push_back(v);
          exact = exact && is_float(m.V(v, 0)) && is_float(m.V(v, 1)) && is_float(m.V(v, 2));
        } else {
          ++shared_corners;
        }
        EXPECT_EQ(h.corner[tri][k], slot);
      }
    }
    ASSERT_EQ(h.num_vertices, corners.size());
    ASSERT_EQ(h.float_coords, exact ? 1 : 0);
    (exact ? float_leaves : double_leaves)++;
    const std::size_t lines = leaf_block_lines(h.num_vertices, exact);
    ASSERT_EQ(static_cast<std::size_t>(n.count), lines);
    next_line += lines;
    // The coordinates, then zeros to the end of the block; the box: the corners' bounds
    // rounded outward to float.
    const std::size_t coord_bytes = (exact ? 12 : 24) * corners.size();
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (std::size_t j = 0; j < corners.size(); ++j) {
      for (int k = 0; k < 3; ++k) {
        const double x = m.V(corners[j], k);
        double stored;
        if (exact) {
          float f;
          std::memcpy(&f, base + kLeafHeaderBytes + 4 * (3 * j + k), 4);
          stored = f;
        } else {
          std::memcpy(&stored, base + kLeafHeaderBytes + 8 * (3 * j + k), 8);
        }
        EXPECT_EQ(stored, x);
        lo[k] = std::min(lo[k], x);
        hi[k] = std::max(hi[k], x);
      }
    }
    for (std::size_t b = kLeafHeaderBytes + coord_bytes; b < 64 * lines; ++b) ASSERT_EQ(base[b], 0) << "byte " << b;
    for (std::size_t b = sizeof(LeafHeader); b < kLeafHeaderBytes; ++b) ASSERT_EQ(base[b], 0) << "byte " << b;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(n.lo[k], round_down_to_float(lo[k]));
      EXPECT_EQ(n.hi[k], round_up_to_float(hi[k]));
      EXPECT_LE(static_cast<double>(n.lo[k]), lo[k]);
      EXPECT_GE(static_cast<double>(n.hi[k]), hi[k]);
    }
  }
  EXPECT_EQ(blocks.size(), next_line);
  EXPECT_GT(float_leaves, 100);  // both kinds, and corners shared within leaves
  EXPECT_GT(double_leaves, 100);
  EXPECT_GT(shared_corners, 1000);
}

TEST(LeafBlocks, SameBytesWhateverTheThreads) {
  // Several chunks of nodes; degenerate faces, open borders and holes, float and double leaves.
  const TriangleMesh m = irregular_mesh(220);
  const std::vector<std::uint8_t> flags = triangle_flags(m, nullptr);
  const Tree tree = lbvh(m);
  ASSERT_GT(tree.nodes.size(), 40000u);
  BvhNodes serial_nodes = tree.nodes;
  const LeafBlocks serial = build_leaf_blocks(m, flags, tree.prims, serial_nodes, 1);
  for (const int threads : {2, 3}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    BvhNodes nodes = tree.nodes;
    const LeafBlocks blocks = build_leaf_blocks(m, flags, tree.prims, nodes, threads);
    ASSERT_EQ(blocks.size(), serial.size());
    EXPECT_EQ(std::memcmp(blocks.data(), serial.data(), 64 * blocks.size()), 0);
    ASSERT_EQ(nodes.size(), serial_nodes.size());
    EXPECT_EQ(std::memcmp(nodes.data(), serial_nodes.data(), sizeof(BvhNode) * nodes.size()), 0);
  }
}

TEST(LeafBlocks, ASingleLeaf) {
  const TriangleMesh m = meshes::make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, 1.0 / 3}},
                                           {{0, 1, 2}, {1, 3, 2}});
  Tree t = lbvh(m);
  ASSERT_TRUE(t.nodes[0].is_leaf());
  const LeafBlocks blocks = build_leaf_blocks(m, std::vector<std::uint8_t>(2, 0), t.prims, t.nodes, 2);
  LeafHeader h;
  std::memcpy(&h, blocks[0].bytes, sizeof h);
  EXPECT_EQ(h.count, 2);
  EXPECT_EQ(h.num_vertices, 4);
  EXPECT_EQ(h.float_coords, 0);  // 1/3 is not a float
  EXPECT_EQ(blocks.size(), leaf_block_lines(4, false));
  EXPECT_EQ(t.nodes[0].first, 0);
  EXPECT_EQ(static_cast<std::size_t>(t.nodes[0].count), blocks.size());
  EXPECT_EQ(t.nodes[0].hi[2], round_up_to_float(1.0 / 3));
}

}  // namespace
}  // namespace breastfit::spatial::detail
