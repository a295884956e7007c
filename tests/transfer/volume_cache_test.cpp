#include "breastfit/transfer/volume_cache.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "breastfit/mesh/boundary.h"
#include "breastfit/model/pose_evaluator.h"
#include "breastfit/transfer/breast_measurements.h"
#include "breastfit/transfer/curve_region.h"
#include "support/default_template.h"
#include "support/grid_mesh.h"

namespace breastfit::transfer {
namespace {

bool same_lists(const mesh::AdjacencyLists& a, const mesh::AdjacencyLists& b) {
  return a.offsets == b.offsets && a.items == b.items;
}

/// A closed circle of n points of radius r around c in the xy plane, lifted onto z = f(x, y).
Points circle_on(const Vec3& c, double r, int n, double (*f)(double, double)) {
  Points P(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    const double x = c.x() + r * std::cos(t), y = c.y() + r * std::sin(t);
    P.row(i) << x, y, f(x, y);
  }
  return P;
}

double bump(double x, double y) { return 20 * std::exp(-(x * x + y * y) / (2 * 15.0 * 15.0)); }
double taller_bump(double x, double y) { return 1.1 * bump(x, y) + 0.002 * x; }

TEST(VolumeCache, TopologyIsTheMeshsOwnAndIsReusedForTheSameTrianglesOnly) {
  TriangleMesh g = test::grid_mesh(6, 2.0, bump);
  VolumeCache cache;
  const auto t = cache.topology(g);
  EXPECT_TRUE(same_lists(t->neighbours, mesh::vertex_neighbours(g)));
  EXPECT_TRUE(same_lists(t->faces, mesh::vertex_faces(g)));
  EXPECT_EQ(cache.misses(), 1);
  g.V *= 1.5;  // other positions, the same triangles: the same topology
  EXPECT_EQ(cache.topology(g), t);
  EXPECT_EQ(cache.hits(), 1);
  const TriangleMesh other = test::grid_mesh(5, 2.0);
  const auto u = cache.topology(other);
  EXPECT_NE(u, t);
  EXPECT_TRUE(same_lists(u->neighbours, mesh::vertex_neighbours(other)));
  TriangleMesh flipped = g;  // one triangle turned: not the same mesh
  std::swap(flipped.F(0, 1), flipped.F(0, 2));
  EXPECT_NE(cache.topology(flipped), t);
  EXPECT_EQ(*cache.boundary_loops(g), mesh::boundary_loops(g));
  EXPECT_EQ(cache.boundary_loops(g), cache.boundary_loops(g));
  // Without a cache: computed afresh, the same lists.
  EXPECT_TRUE(same_lists(topology_of(g, nullptr)->neighbours, t->neighbours));
}

TEST(VolumeCache, FillFactorisationIsReusedForAnEqualMatrixOnly) {
  const int n = 30;
  std::vector<Eigen::Triplet<double>> trip;
  for (int i = 0; i < n; ++i) {
    trip.emplace_back(i, i, 3.0);
    if (i + 1 < n) {
      trip.emplace_back(i, i + 1, -1.0);
      trip.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  VolumeCache cache;
  const auto s = cache.fill_solver(A);
  ASSERT_EQ(s->info(), Eigen::Success);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1, 2);
  EXPECT_LT((A * s->solve(b) - b).norm(), 1e-12);
  const Eigen::SparseMatrix<double> copy = A;
  EXPECT_EQ(cache.fill_solver(copy), s);
  EXPECT_EQ(cache.hits(), 1);
  Eigen::SparseMatrix<double> changed = A;
  changed.coeffRef(3, 3) = 4.0;  // same pattern, another value: factorised again
  const auto t = cache.fill_solver(changed);
  EXPECT_NE(t, s);
  EXPECT_LT((changed * t->solve(b) - b).norm(), 1e-12);
  EXPECT_EQ(cache.misses(), 2);
  EXPECT_EQ(cache.fill_solver(A), s);  // the first is still kept
}

TEST(VolumeCache, CurveVolumesAreTheSameBitsWithACache) {
  const Points curve = circle_on(Vec3(0.2, -0.3, 0), 35, 400, bump);
  const Points curve2 = circle_on(Vec3(0.2, -0.3, 0), 35, 400, taller_bump);
  const TriangleMesh g = test::grid_mesh(14, 5.0, bump);
  const TriangleMesh g2 = test::grid_mesh(14, 5.0, taller_bump);  // the same triangles
  VolumeCache cache;
  for (const ChestWallFill fill : {ChestWallFill::Membrane, ChestWallFill::ThinPlate}) {
    CurveVolumeOptions o;
    o.volume.fill = fill;
    o.volume.margin_mm = fill == ChestWallFill::ThinPlate ? 6.0 : 0.0;
    const CurveVolume a = curve_volume(g, curve, o);
    const CurveVolume b = curve_volume(g2, curve2, o);
    ASSERT_GT(a.volume_ml, 0);
    EXPECT_GT(b.volume_ml, a.volume_ml);
    for (int round = 0; round < 2; ++round) {  // the second round from the cache
      EXPECT_EQ(curve_volume(g, curve, o, &cache).volume_ml, a.volume_ml) << round;
      EXPECT_EQ(curve_volume(g2, curve2, o, &cache).volume_ml, b.volume_ml) << round;
    }
  }
  EXPECT_GT(cache.hits(), 0);
}

TEST(VolumeCache, BreastVolumesOfTheTemplateAreTheSameBitsWithACache) {
  const model::RiggedModel& m = *test::default_template();
  model::PoseParams p = model::PoseParams::identity(m);
  VolumeCache cache;
  for (int k = 0; k < 3; ++k) {
    if (k > 0 && m.blendshapes.size() > 0) p.alpha[0] = 0.3 * k * std::min(1.0, m.blendshapes[0].hi);
    const Points V = model::pose_vertices(m, p);
    const BreastMeasurements fresh = measure_breasts(m, V);
    const BreastMeasurements cached = measure_breasts(m, V, {}, &cache);
    ASSERT_TRUE(fresh.right.volume_ml && fresh.left.volume_ml);
    EXPECT_EQ(*cached.right.volume_ml, *fresh.right.volume_ml) << k;
    EXPECT_EQ(*cached.left.volume_ml, *fresh.left.volume_ml) << k;
  }
  EXPECT_GT(cache.hits(), 0);  // the template's own topology at least
}

}  // namespace
}  // namespace breastfit::transfer
