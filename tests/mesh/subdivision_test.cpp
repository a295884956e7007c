#include "breastfit/mesh/subdivision.h"

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"
#include "breastfit/core/rng.h"
#include "breastfit/mesh/boundary.h"
#include "breastfit/mesh/components.h"
#include "support/toy_model.h"

namespace breastfit::mesh {
namespace {

TriangleMesh open_grid() {
  // 3 x 3 quads in the z = 0 plane, 10 mm cells, counter-clockwise seen from +z.
  TriangleMesh m;
  m.V.resize(16, 3);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) m.V.row(j * 4 + i) << 10.0 * i, 10.0 * j, 0.0;
  m.F.resize(18, 3);
  int f = 0;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const Index a = j * 4 + i, b = a + 1, c = a + 5, d = a + 4;
      m.F.row(f++) << a, b, c;
      m.F.row(f++) << a, c, d;
    }
  return m;
}

TEST(Subdivision, CountsAndTopology) {
  const auto model = test::make_toy_model();
  const TriangleMesh& m = model.rest;
  for (bool loop : {false, true}) {
    const TriangleMesh s = subdivide(m, loop);
    EXPECT_EQ(s.num_faces(), 4 * m.num_faces());
    // V' = V + E; Euler characteristic V - E + F is preserved.
    const Index edges = (3 * m.num_faces() + static_cast<Index>(mesh::boundary_edges(m.F).size())) / 2;
    EXPECT_EQ(s.num_vertices(), m.num_vertices() + edges);
    const Index edges_s = (3 * s.num_faces() + static_cast<Index>(mesh::boundary_edges(s.F).size())) / 2;
    EXPECT_EQ(s.num_vertices() - edges_s + s.num_faces(), m.num_vertices() - edges + m.num_faces());
    EXPECT_EQ(mesh::boundary_loops(s).size(), mesh::boundary_loops(m).size());
    EXPECT_EQ(mesh::connected_components(s).count(), 1);
    EXPECT_NEAR(median_edge_length(s), 0.5 * median_edge_length(m), 0.2 * median_edge_length(m));
  }
}

TEST(Subdivision, MidpointKeepsSurfacePointsExactly) {
  const auto model = test::make_toy_model();
  const TriangleMesh s = subdivide(model.rest, false);
  Rng rng(5);
  for (int i = 0; i < 200; ++i) {
    SurfacePoint p;
    p.face = static_cast<Index>(rng.below(static_cast<std::uint64_t>(model.rest.num_faces())));
    double a = rng.uniform(), b = rng.uniform();
    if (a + b > 1) a = 1 - a, b = 1 - b;
    p.bary = Vec3(1 - a - b, a, b);
    const SurfacePoint q = refine_surface_point(p);
    EXPECT_NEAR(q.bary.sum(), 1.0, 1e-12);
    EXPECT_GE(q.bary.minCoeff(), -1e-12);
    EXPECT_EQ(q.face / 4, p.face);
    EXPECT_LT((q.position(s.V, s.F) - p.position(model.rest.V, model.rest.F)).norm(), 1e-9);
  }
}

TEST(Subdivision, LoopSmoothsButStaysClose) {
  const auto model = test::make_toy_model();
  TriangleMesh s = model.rest;
  for (int k = 0; k < 2; ++k) s = subdivide(s, true);
  // The toy torso is an elliptic cylinder (radii 60 x 40): refined vertices stay near it.
  double worst = 0;
  for (Index v = 0; v < s.num_vertices(); ++v) {
    if (s.V(v, 2) < 30.0 || s.V(v, 2) > 210.0) continue;  // away from the end caps
    const double x = s.V(v, 0) / 60.0, y = s.V(v, 1) / 40.0;
    worst = std::max(worst, std::abs(std::sqrt(x * x + y * y) - 1.0));
  }
  EXPECT_LT(worst, 0.1);
}

TEST(Subdivision, LoopBoundaryIsACubicBSpline) {
  const TriangleMesh g = open_grid();
  const TriangleMesh s = subdivide(g, true);
  // A straight border stays straight (y = 0 row) and the flat grid stays flat.
  for (Index v = 0; v < s.num_vertices(); ++v) EXPECT_NEAR(s.V(v, 2), 0.0, 1e-12);
  const auto border = mesh::boundary_vertices(s);
  int on_bottom = 0;
  for (Index v = 0; v < s.num_vertices(); ++v)
    if (border[static_cast<size_t>(v)] && std::abs(s.V(v, 1)) < 1e-12) ++on_bottom;
  EXPECT_EQ(on_bottom, 5);  // 2 inner border vertices + 3 edge points (the corners round off)
  // Interior vertex of a regular flat grid does not move.
  EXPECT_NEAR(s.V(5, 0), 10.0, 1e-9);
  EXPECT_NEAR(s.V(5, 1), 10.0, 1e-9);
}

TEST(Subdivision, RejectsBadIndices) {
  TriangleMesh m = open_grid();
  m.F(0, 0) = 99;
  EXPECT_THROW(subdivide(m, true), InvalidInput);
}

}  // namespace
}  // namespace breastfit::mesh
