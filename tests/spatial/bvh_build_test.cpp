// The BVH build pieces: outward float rounding, the Morton (LBVH) topology against a
// straightforward reference, the mesh-based Morton order against the box-based build, and the
// tree invariants.
#include "breastfit/spatial/detail/bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <vector>

#include "breastfit/core/rng.h"
#include "breastfit/spatial/detail/triangle_tables.h"
#include "spatial/spatial_test_meshes.h"

namespace breastfit::spatial::detail {
namespace {

namespace meshes = breastfit::test::spatial_meshes;

float reference_round_down(double x) {
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity())
                                    : f;
}
float reference_round_up(double x) {
  const auto f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity())
                                    : f;
}

void expect_rounding_matches(double x) {
  const float down = round_down_to_float(x), up = round_up_to_float(x);
  const float ref_down = reference_round_down(x), ref_up = reference_round_up(x);
  // Bitwise (also the sign of zero).
  EXPECT_EQ(std::memcmp(&down, &ref_down, sizeof(float)), 0) << x;
  EXPECT_EQ(std::memcmp(&up, &ref_up, sizeof(float)), 0) << x;
  EXPECT_LE(static_cast<double>(down), x);
  EXPECT_GE(static_cast<double>(up), x);
}

TEST(BvhBuild, OutwardRoundingMatchesNextafter) {
  constexpr double kMax = std::numeric_limits<float>::max();
  constexpr double kDenorm = std::numeric_limits<float>::denorm_min();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (const double x : {0.0, -0.0, 1.0, -1.0, 0.1, -0.1, 1e-300, -1e-300, kDenorm, -kDenorm,
                         0.5 * kDenorm, -0.5 * kDenorm, kMax, -kMax, kMax * (1 + 1e-12),
                         -kMax * (1 + 1e-12), 1e300, -1e300, kInf, -kInf}) {
    expect_rounding_matches(x);
  }
  Rng rng(5);
  for (int i = 0; i < 200000; ++i) {
    double x;
    const std::uint64_t bits = rng.next_u64();
    std::memcpy(&x, &bits, sizeof x);
    if (std::isnan(x)) continue;
    expect_rounding_matches(x);
    expect_rounding_matches(rng.uniform(-1000.0, 1000.0));
  }
}

/// The LBVH topology as first written: same traversal, plain binary search.
BvhNodes reference_topology(const std::vector<std::uint64_t>& keys, int max_leaf, int& depth) {
  BvhNodes nodes(2);
  depth = 0;
  struct Range {
    std::int32_t node, begin, end;
    int depth;
  };
  std::vector<Range> stack{{0, 0, static_cast<std::int32_t>(keys.size()), 0}};
  while (!stack.empty()) {
    const Range r = stack.back();
    stack.pop_back();
    depth = std::max(depth, r.depth);
    if (r.end - r.begin <= max_leaf) {
      nodes[r.node].first = r.begin;
      nodes[r.node].count = r.end - r.begin;
      continue;
    }
    std::int32_t mid;
    if (keys[r.begin] == keys[r.end - 1]) {
      mid = r.begin + (r.end - r.begin) / 2;
    } else {
      const std::uint64_t mask = std::uint64_t{1}
                                 << (63 - __builtin_clzll(keys[r.begin] ^ keys[r.end - 1]));
      mid = r.begin;
      while (!(keys[mid] & mask)) ++mid;
    }
    const auto left = static_cast<std::int32_t>(nodes.size());
    nodes.resize(nodes.size() + 2);
    nodes[r.node].first = left;
    nodes[r.node].count = 0;
    stack.push_back({left + 1, mid, r.end, r.depth + 1});
    stack.push_back({left, r.begin, mid, r.depth + 1});
  }
  return nodes;
}

TEST(BvhBuild, MortonTopologyMatchesReference) {
  Rng rng(6);
  for (const int max_leaf : {1, 2, 4, 8}) {
    for (const std::size_t n : {1u, 2u, 5u, 100u, 5000u, 70000u}) {
      for (const int distinct_bits : {2, 12, 63}) {  // few distinct keys → equal-key halving
        std::vector<std::uint64_t> keys(n);
        for (auto& k : keys) {
          k = rng.next_u64() >> 1;
          if (distinct_bits < 63) k &= ~((std::uint64_t{1} << (63 - distinct_bits)) - 1);
        }
        std::sort(keys.begin(), keys.end());
        int ref_depth = 0;
        const BvhNodes ref = reference_topology(keys, max_leaf, ref_depth);
        // Serially, and with subtrees built concurrently and spliced in: the same nodes.
        for (const int threads : {1, 2, 3}) {
          BvhNodes nodes;
          const int depth = build_morton_topology(keys, max_leaf, nodes, threads);
          EXPECT_EQ(depth, ref_depth) << threads << " threads";
          ASSERT_EQ(nodes.size(), ref.size()) << threads << " threads";
          for (std::size_t i = 0; i < nodes.size(); ++i) {
            ASSERT_EQ(nodes[i].first, ref[i].first) << "node " << i << ", " << threads << " threads";
            ASSERT_EQ(nodes[i].count, ref[i].count) << "node " << i << ", " << threads << " threads";
          }
        }
      }
    }
  }
  BvhNodes none;
  EXPECT_EQ(build_morton_topology({}, 4, none), 0);
  EXPECT_TRUE(none.empty());
}

std::vector<TriangleMesh> test_meshes() {
  std::vector<TriangleMesh> out = {meshes::noisy_sheet(40, 2.0, 1.0, 0.1, 3),
                                   meshes::icosphere(4, 80.0, Vec3(3, -2, 1)),
                                   meshes::random_soup(3000, 100.0, 3.0, 4)};
  // Flat in z, and duplicated triangles (equal Morton codes).
  TriangleMesh flat = meshes::noisy_sheet(20, 1.0, 0.0, 0.0, 5);
  TriangleMesh dup = flat;
  dup.F.conservativeResize(2 * flat.num_faces(), 3);
  dup.F.bottomRows(flat.num_faces()) = flat.F;
  out.push_back(flat);
  out.push_back(dup);
  return out;
}

TEST(BvhBuild, MeshMortonOrderIsTheBoxBuildOrder) {
  std::vector<TriangleMesh> meshes = test_meshes();
  meshes.push_back(meshes::icosphere(6, 50.0));  // 82k faces: several chunks of the parallel loops
  for (const TriangleMesh& m : meshes) {
    const MortonSorted sorted = triangle_morton_order(m);
    const MortonSorted parallel = triangle_morton_order(m, 3);
    EXPECT_EQ(parallel.codes, sorted.codes);
    EXPECT_EQ(parallel.prims, sorted.prims);
    ASSERT_EQ(sorted.codes.size(), static_cast<std::size_t>(m.num_faces()));
    EXPECT_TRUE(std::is_sorted(sorted.codes.begin(), sorted.codes.end()));
    const Bvh bvh = Bvh::build(triangle_boxes(m));  // Morton by default
    ASSERT_EQ(bvh.prims.size(), sorted.prims.size());
    for (std::size_t i = 0; i < sorted.prims.size(); ++i) {
      ASSERT_EQ(static_cast<std::int32_t>(sorted.prims[i]), bvh.prims[i]) << "slot " << i;
      if (i > 0 && sorted.codes[i] == sorted.codes[i - 1]) {
        EXPECT_LT(sorted.prims[i - 1], sorted.prims[i]);  // ties by face index
      }
    }
  }
}

TEST(BvhBuild, BoxesContainTheirPrimitivesAndChildren) {
  for (const TriangleMesh& m : test_meshes()) {
    for (const BvhBuildMethod method : {BvhBuildMethod::Morton, BvhBuildMethod::Sah}) {
      BvhBuildOptions options;
      options.method = method;
      const std::vector<PrimBox> boxes = triangle_boxes(m);
      const Bvh bvh = Bvh::build(boxes, options);
      std::vector<std::int32_t> prims = bvh.prims;
      std::sort(prims.begin(), prims.end());
      std::vector<std::int32_t> all(boxes.size());
      std::iota(all.begin(), all.end(), 0);
      EXPECT_EQ(prims, all);
      std::size_t leaf_slots = 0;
      for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
        if (i == 1) continue;
        const BvhNode& n = bvh.nodes[i];
        if (n.is_leaf()) {
          leaf_slots += static_cast<std::size_t>(n.count);
          EXPECT_LE(n.count, options.max_leaf_size);
          for (std::int32_t s = n.first; s < n.first + n.count; ++s) {
            for (int k = 0; k < 3; ++k) {
              EXPECT_LE(static_cast<double>(n.lo[k]), boxes[bvh.prims[s]].lo[k]);
              EXPECT_GE(static_cast<double>(n.hi[k]), boxes[bvh.prims[s]].hi[k]);
            }
          }
        } else {
          for (const BvhNode& c : {bvh.nodes[n.first], bvh.nodes[n.first + 1]}) {
            for (int k = 0; k < 3; ++k) {
              EXPECT_LE(n.lo[k], c.lo[k]);
              EXPECT_GE(n.hi[k], c.hi[k]);
            }
          }
        }
      }
      EXPECT_EQ(leaf_slots, boxes.size());
    }
  }
}

}  // namespace
}  // namespace breastfit::spatial::detail
