// The four-wide tree refitted to moved vertices: its leaf blocks and boxes are, byte for byte,
// those a build over the same tree (the same leaves) makes at the new positions; a block stored in
// floats refuses corners that are not floats.
#include "breastfit/spatial/detail/bvh4_refit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "breastfit/spatial/detail/triangle_tables.h"
#include "spatial/spatial_test_meshes.h"

namespace breastfit::spatial::detail {
namespace {

namespace meshes = breastfit::test::spatial_meshes;

/// The closest-point index's tree over `m` built on the leaves of `topology` (an LBVH's nodes
/// before their leaves get blocks) and `prims`.
struct Built {
  LeafBlocks blocks;
  Bvh4Nodes wide;
};

Built build_on(const TriangleMesh& m, const std::vector<std::uint8_t>& flags, const std::vector<std::uint32_t>& prims,
               BvhNodes topology) {
  Built b;
  b.blocks = build_leaf_blocks(m, flags, prims, topology, 1);
  fit_inner_boxes(topology);
  b.wide = collapse_to_bvh4(topology);
  return b;
}

void expect_same_bytes(const Built& a, const Built& b) {
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  EXPECT_EQ(std::memcmp(a.blocks.data(), b.blocks.data(), a.blocks.size() * sizeof(CacheLine)), 0);
  ASSERT_EQ(a.wide.size(), b.wide.size());
  EXPECT_EQ(std::memcmp(a.wide.data(), b.wide.data(), a.wide.size() * sizeof(Bvh4Node)), 0);
}

TEST(Bvh4Refit, BlocksAndBoxesAreThoseOfABuildAtTheNewPositions) {
  // A sheet with an open border and holes, every 13th face degenerate at first.
  TriangleMesh m = meshes::noisy_sheet(50, 1.0, 0.4, 0.05, 91);
  for (Index f = 0; f < m.num_faces(); f += 13) m.F(f, 2) = m.F(f, 1);
  const std::vector<std::uint8_t> flags = triangle_flags(m, nullptr);
  MortonSorted sorted = triangle_morton_order(m);
  BvhNodes topology;
  build_morton_topology(sorted.codes, kMaxLeafSize, topology);
  Built tree = build_on(m, flags, sorted.prims, topology);

  // Bent, and face 1 made degenerate (its corners together).
  TriangleMesh moved = m;
  for (Index i = 0; i < moved.V.rows(); ++i)
    moved.V.row(i) += Vec3(0.3 * std::sin(m.V(i, 1)), 0.2 * std::cos(m.V(i, 0)), 0.5 * std::sin(0.3 * m.V(i, 0))).transpose();
  moved.V.row(moved.F(1, 1)) = moved.V.row(moved.F(1, 0));
  moved.V.row(moved.F(1, 2)) = moved.V.row(moved.F(1, 0));
  std::vector<std::uint8_t> moved_flags = flags;
  mark_degenerate_faces(moved, moved_flags);
  EXPECT_EQ(moved_flags, triangle_flags(moved, nullptr));  // only the degenerate bits moved
  EXPECT_NE(moved_flags, flags);
  ASSERT_TRUE(refit_bvh4(moved, moved_flags, tree.blocks, tree.wide));
  expect_same_bytes(tree, build_on(moved, moved_flags, sorted.prims, topology));
}

TEST(Bvh4Refit, FloatBlocksTakeFloatsAndRefuseTheRest) {
  TriangleMesh m = meshes::noisy_sheet(30, 1.0, 0.4, 0.05, 92);
  m.V = m.V.cast<float>().cast<double>();
  const std::vector<std::uint8_t> flags = triangle_flags(m, nullptr);
  MortonSorted sorted = triangle_morton_order(m);
  BvhNodes topology;
  build_morton_topology(sorted.codes, kMaxLeafSize, topology);
  Built tree = build_on(m, flags, sorted.prims, topology);
  ASSERT_TRUE(reinterpret_cast<const LeafHeader*>(tree.blocks[0].bytes)->float_coords);

  TriangleMesh doubled = m;
  doubled.V *= 2.0;  // floats still
  ASSERT_TRUE(refit_bvh4(doubled, flags, tree.blocks, tree.wide));
  expect_same_bytes(tree, build_on(doubled, flags, sorted.prims, topology));

  TriangleMesh off = doubled;
  off.V.array() += 1e-9;  // no longer floats: a float block cannot hold them
  EXPECT_FALSE(refit_bvh4(off, flags, tree.blocks, tree.wide));
}

}  // namespace
}  // namespace breastfit::spatial::detail
