// Per-triangle boundary flags against a plain edge-count map, on meshes with holes,
// non-manifold edges, duplicated and inconsistently oriented faces and repeated corners.
#include "breastfit/spatial/detail/triangle_tables.h"

#include <gtest/gtest.h>

#include <array>
#include <map>
#include <utility>
#include <vector>

#include "breastfit/core/rng.h"
#include "spatial/spatial_test_meshes.h"

namespace breastfit::spatial::detail {
namespace {

namespace meshes = breastfit::test::spatial_meshes;

/// Reference: an edge is open when exactly one face corner uses it (either direction).
void reference_boundary(const TriangleMesh& m, std::vector<std::uint8_t>& edge_bits,
                        std::vector<std::uint8_t>& vertex_boundary) {
  std::map<std::pair<Index, Index>, int> uses;
  for (Index f = 0; f < m.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index u = m.F(f, k), w = m.F(f, (k + 1) % 3);
      ++uses[std::minmax(u, w)];
    }
  }
  static constexpr std::uint8_t kBit[3] = {kFlagBoundaryEdge01, kFlagBoundaryEdge12,
                                           kFlagBoundaryEdge20};
  edge_bits.assign(m.num_faces(), 0);
  vertex_boundary.assign(m.num_vertices(), 0);
  for (Index f = 0; f < m.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index u = m.F(f, k), w = m.F(f, (k + 1) % 3);
      if (u != w && uses[std::minmax(u, w)] == 1) {
        edge_bits[f] |= kBit[k];
        vertex_boundary[u] = vertex_boundary[w] = 1;
      }
    }
  }
}

void expect_flags_match(const TriangleMesh& m) {
  std::vector<std::uint8_t> vb;
  const std::vector<std::uint8_t> flags = triangle_flags(m, &vb);
  std::vector<std::uint8_t> ref_bits, ref_vb;
  reference_boundary(m, ref_bits, ref_vb);
  ASSERT_EQ(flags.size(), ref_bits.size());
  constexpr std::uint8_t kEdges = kFlagBoundaryEdge01 | kFlagBoundaryEdge12 | kFlagBoundaryEdge20;
  for (Index f = 0; f < m.num_faces(); ++f) {
    ASSERT_EQ(flags[f] & kEdges, ref_bits[f]) << "face " << f;
  }
  EXPECT_EQ(vb, ref_vb);
  // Without the vertex output the face flags are the same.
  EXPECT_EQ(triangle_flags(m, nullptr), flags);
}

/// A sheet with holes, then damaged: extra fins on existing edges (non-manifold), duplicated
/// and flipped faces, faces with a repeated corner, and isolated vertices.
TriangleMesh damaged_sheet(std::uint64_t seed) {
  TriangleMesh m = meshes::noisy_sheet(25, 1.0, 0.3, 0.15, seed);
  Rng rng(seed);
  std::vector<std::array<Index, 3>> extra;
  const Index nv = m.num_vertices();
  for (int i = 0; i < 60; ++i) {
    const auto f = static_cast<Index>(rng.below(static_cast<std::uint64_t>(m.num_faces())));
    const Index a = m.F(f, 0), b = m.F(f, 1), c = m.F(f, 2);
    switch (i % 5) {
      case 0: extra.push_back({a, b, static_cast<Index>(rng.below(nv))}); break;  // fin
      case 1: extra.push_back({a, b, c}); break;                                  // duplicate
      case 2: extra.push_back({b, a, c}); break;                                  // flipped
      case 3: extra.push_back({a, a, b}); break;                                  // repeated corner
      default: extra.push_back({c, c, c}); break;                                 // a point
    }
  }
  const Index nf = m.num_faces();
  m.F.conservativeResize(nf + static_cast<Index>(extra.size()), 3);
  for (std::size_t i = 0; i < extra.size(); ++i) {
    for (int k = 0; k < 3; ++k) m.F(nf + static_cast<Index>(i), k) = extra[i][k];
  }
  m.V.conservativeResize(nv + 5, 3);  // isolated vertices
  m.V.bottomRows(5).setOnes();
  return m;
}

TEST(TriangleFlags, MatchEdgeCountsOnSheetsWithHoles) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    expect_flags_match(meshes::noisy_sheet(30, 1.0, 0.5, 0.2, seed));
  }
}

TEST(TriangleFlags, MatchEdgeCountsOnDamagedMeshes) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) expect_flags_match(damaged_sheet(seed));
}

TEST(TriangleFlags, MatchEdgeCountsOnSoupsAndClosedMeshes) {
  expect_flags_match(meshes::random_soup(500, 10.0, 1.0, 7));
  expect_flags_match(meshes::icosphere(3, 10.0));
  // Corners drawn from a few vertices: many coincident and repeated edges.
  TriangleMesh m = meshes::random_soup(400, 10.0, 1.0, 8);
  Rng rng(9);
  for (Index f = 0; f < m.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) m.F(f, k) = static_cast<Index>(rng.below(12));
  }
  expect_flags_match(m);
}

TEST(TriangleFlags, ClosedSphereHasNoOpenEdge) {
  std::vector<std::uint8_t> vb;
  const std::vector<std::uint8_t> flags = triangle_flags(meshes::icosphere(2, 1.0), &vb);
  for (const std::uint8_t f : flags) EXPECT_EQ(f & ~kFlagDegenerate, 0);
  for (const std::uint8_t v : vb) EXPECT_EQ(v, 0);
}

}  // namespace
}  // namespace breastfit::spatial::detail
