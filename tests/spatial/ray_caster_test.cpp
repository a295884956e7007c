#include "breastfit/spatial/ray_caster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/core/rng.h"
#include "spatial/spatial_test_meshes.h"

namespace breastfit::spatial {
namespace {

namespace meshes = breastfit::test::spatial_meshes;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Independent reference: plane intersection then inside test, in long double; all hits sorted.
std::vector<std::pair<long double, Index>> brute_hits(const TriangleMesh& m, const Vec3& o,
                                                      const Vec3& d, long double t_min,
                                                      long double t_max) {
  using L = Eigen::Matrix<long double, 3, 1>;
  std::vector<std::pair<long double, Index>> hits;
  const L O = o.cast<long double>(), D = d.cast<long double>();
  for (Index f = 0; f < m.num_faces(); ++f) {
    const L a = m.V.row(m.F(f, 0)).transpose().cast<long double>();
    const L b = m.V.row(m.F(f, 1)).transpose().cast<long double>();
    const L c = m.V.row(m.F(f, 2)).transpose().cast<long double>();
    const L n = (b - a).cross(c - a);
    const long double den = n.dot(D);
    if (den == 0) continue;
    const long double t = n.dot(a - O) / den;
    if (t < t_min || t > t_max) continue;
    const L x = O + t * D;
    // Inside: same-side tests against the three edges.
    const long double s0 = n.dot((b - a).cross(x - a)), s1 = n.dot((c - b).cross(x - b)),
                      s2 = n.dot((a - c).cross(x - c));
    if (s0 >= 0 && s1 >= 0 && s2 >= 0) hits.emplace_back(t, f);
  }
  std::sort(hits.begin(), hits.end());
  return hits;
}

void expect_matches_brute_force(const TriangleMesh& m, int num_rays, std::uint64_t seed) {
  const RayCaster caster(m);
  Rng rng(seed);
  const Vec3 lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  const Vec3 mid = 0.5 * (lo + hi);
  const double ext = (hi - lo).maxCoeff();
  int hits = 0, misses = 0;
  for (int i = 0; i < num_rays; ++i) {
    const Vec3 o = mid + 1.5 * ext * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1),
                                          rng.uniform(-1, 1));
    // Aim at a random surface point most of the time so that rays do hit.
    Vec3 d = i % 4 == 3 ? meshes::random_unit(rng)
                        : Vec3(meshes::random_surface_point(m, rng) - o).normalized();
    if (i % 7 == 0) d *= 3.0;  // non-unit directions: t in units of |dir|
    const double t_max = i % 5 == 0 ? 0.7 * ext : kInf;
    const auto ref = brute_hits(m, o, d, 0, t_max);
    const auto hit = caster.intersect(o, d, t_max);
    if (ref.empty()) {
      // Only a grazing edge hit within the tolerance may differ.
      if (hit) {
        ADD_FAILURE() << "ray " << i << " hit face " << hit->face << " at t " << hit->t;
      }
      ++misses;
      continue;
    }
    ASSERT_TRUE(hit.has_value()) << "ray " << i;
    ++hits;
    const double t_ref = static_cast<double>(ref[0].first);
    EXPECT_NEAR(hit->t, t_ref, 1e-9 * std::max(1.0, t_ref)) << "ray " << i;
    const bool unique = ref.size() == 1 || ref[1].first > ref[0].first * (1 + 1e-9L);
    if (unique) {
      EXPECT_EQ(hit->face, ref[0].second) << "ray " << i;
    }
    EXPECT_NEAR(hit->bary.sum(), 1.0, 1e-12);
    EXPECT_GE(hit->bary.minCoeff(), 0.0);
    EXPECT_LT((hit->point - (o + hit->t * d)).norm(), 1e-8 * std::max(1.0, ext));
  }
  EXPECT_GT(hits, num_rays / 2);
  EXPECT_GT(misses, 0);
}

TEST(RayCaster, MatchesBruteForceOnSphere) {
  expect_matches_brute_force(meshes::icosphere(4, 100.0, Vec3(5, 6, 7)), 1500, 1);
}

TEST(RayCaster, MatchesBruteForceOnRandomSoup) {
  expect_matches_brute_force(meshes::random_soup(1500, 100.0, 6.0, 2), 1500, 3);
}

TEST(RayCaster, MatchesBruteForceOnNoisySheetWithHoles) {
  expect_matches_brute_force(meshes::noisy_sheet(30, 2.0, 0.7, 0.2, 4), 1500, 5);
}

TEST(RayCaster, AxisAlignedRaysAndBothSides) {
  const TriangleMesh sheet = meshes::noisy_sheet(4, 1.0, 0.0, 0.0, 1);  // z = 0, [0, 4]²
  const RayCaster caster(sheet);
  // Straight down and straight up (back side), exactly axis-aligned.
  auto down = caster.intersect(Vec3(1.3, 2.6, 5.0), Vec3(0, 0, -1));
  ASSERT_TRUE(down.has_value());
  EXPECT_DOUBLE_EQ(down->t, 5.0);
  EXPECT_NEAR(down->point.x(), 1.3, 1e-12);
  auto up = caster.intersect(Vec3(1.3, 2.6, -2.0), Vec3(0, 0, 1));
  ASSERT_TRUE(up.has_value());
  EXPECT_DOUBLE_EQ(up->t, 2.0);
  EXPECT_EQ(up->face, down->face);
  // Pointing away, beside the sheet, and too short.
  EXPECT_FALSE(caster.intersect(Vec3(1.3, 2.6, 5.0), Vec3(0, 0, 1)).has_value());
  EXPECT_FALSE(caster.intersect(Vec3(5.5, 2.0, 5.0), Vec3(0, 0, -1)).has_value());
  EXPECT_FALSE(caster.intersect(Vec3(1.3, 2.6, 5.0), Vec3(0, 0, -1), 4.9).has_value());
  // Through a shared vertex (grid point): still a hit.
  auto vertex = caster.intersect(Vec3(2.0, 2.0, 1.0), Vec3(0, 0, -1));
  ASSERT_TRUE(vertex.has_value());
  EXPECT_NEAR(vertex->bary.maxCoeff(), 1.0, 1e-12);
  // Through the diagonal edge of a cell: hits, whichever of the two triangles.
  auto edge = caster.intersect(Vec3(1.5, 1.5, 1.0), Vec3(0, 0, -1));
  ASSERT_TRUE(edge.has_value());
  EXPECT_DOUBLE_EQ(edge->t, 1.0);
  // Parallel to the sheet in its plane: no hit (zero determinant).
  EXPECT_FALSE(caster.intersect(Vec3(-1.0, 2.5, 0.0), Vec3(1, 0, 0)).has_value());
}

TEST(RayCaster, NearestOfSeveralLayers) {
  // Concentric spheres: from outside, the outer one is hit first; from the centre the inner.
  TriangleMesh outer = meshes::icosphere(3, 50.0), inner = meshes::icosphere(3, 20.0);
  TriangleMesh both;
  both.V.resize(outer.num_vertices() + inner.num_vertices(), 3);
  both.V << outer.V, inner.V;
  both.F.resize(outer.num_faces() + inner.num_faces(), 3);
  both.F << outer.F, (inner.F.array() + outer.num_vertices()).matrix();
  const RayCaster caster(both);
  Rng rng(9);
  for (int i = 0; i < 200; ++i) {
    const Vec3 d = meshes::random_unit(rng);
    auto from_out = caster.intersect(-100.0 * d, d);
    ASSERT_TRUE(from_out.has_value());
    EXPECT_LT(from_out->face, outer.num_faces());
    EXPECT_NEAR(from_out->point.norm(), 50.0, 1.5);
    auto from_centre = caster.intersect(Vec3::Zero(), d);
    ASSERT_TRUE(from_centre.has_value());
    EXPECT_GE(from_centre->face, outer.num_faces());
    EXPECT_NEAR(from_centre->t, 20.0, 0.6);
  }
}

TEST(RayCaster, OccludedAgreesWithBruteForce) {
  const TriangleMesh m = meshes::noisy_sheet(20, 2.0, 2.0, 0.2, 6);
  const RayCaster caster(m);
  Rng rng(10);
  int blocked = 0, clear = 0;
  for (int i = 0; i < 2000; ++i) {
    // Surface point to a "camera" above or below the sheet.
    const Vec3 p = meshes::random_surface_point(m, rng);
    const Vec3 cam(rng.uniform(-10, 50), rng.uniform(-10, 50), rng.uniform(-30, 30));
    const double eps = 1e-6;
    const Vec3 d = cam - p;
    const double len = d.norm();
    const auto ref = brute_hits(m, p, d / len, eps, len - eps);
    const bool occ = caster.occluded(p, cam, eps);
    EXPECT_EQ(occ, !ref.empty()) << "pair " << i;
    (occ ? blocked : clear)++;
  }
  EXPECT_GT(blocked, 100);
  EXPECT_GT(clear, 100);
  // A surface point does not occlude itself; a point below an opaque sheet is hidden.
  const TriangleMesh flat = meshes::noisy_sheet(4, 1.0, 0.0, 0.0, 1);
  const RayCaster flat_caster(flat);
  EXPECT_FALSE(flat_caster.occluded(Vec3(1.2, 1.7, 0.0), Vec3(2, 2, 10)));
  EXPECT_TRUE(flat_caster.occluded(Vec3(1.2, 1.7, -1.0), Vec3(2, 2, 10)));
  EXPECT_FALSE(flat_caster.occluded(Vec3(1.2, 1.7, -1.0), Vec3(1.2, 1.7, -1.0)));
}

TEST(RayCaster, SingleTriangleHelper) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  auto hit = intersect_ray_triangle(Vec3(0.25, 0.5, 2), Vec3(0, 0, -1), a, b, c, 0, kInf);
  ASSERT_TRUE(hit.has_value());
  EXPECT_DOUBLE_EQ(hit->t, 2.0);
  EXPECT_NEAR(hit->bary[0], 0.25, 1e-15);
  EXPECT_NEAR(hit->bary[1], 0.25, 1e-15);
  EXPECT_NEAR(hit->bary[2], 0.5, 1e-15);
  EXPECT_FALSE(intersect_ray_triangle(Vec3(0.8, 0.8, 2), Vec3(0, 0, -1), a, b, c, 0, kInf));
  EXPECT_FALSE(intersect_ray_triangle(Vec3(0.25, 0.5, 2), Vec3(0, 0, -1), a, b, c, 0, 1.5));
  EXPECT_FALSE(intersect_ray_triangle(Vec3(0.25, 0.5, 2), Vec3(0, 0, -1), a, a, c, 0, kInf));
}

TEST(RayCaster, RejectsBadInput) {
  TriangleMesh empty;
  empty.V = Points::Zero(3, 3);
  EXPECT_THROW(RayCaster{empty}, InvalidInput);
  TriangleMesh nan_mesh = meshes::icosphere(1, 1.0);
  nan_mesh.V(0, 2) = std::nan("");
  EXPECT_THROW(RayCaster{nan_mesh}, InvalidInput);
  const RayCaster caster(meshes::icosphere(1, 1.0));
  EXPECT_THROW(caster.intersect(Vec3::Zero(), Vec3::Zero()), InvalidInput);
  EXPECT_THROW(caster.intersect(Vec3(kInf, 0, 0), Vec3(1, 0, 0)), InvalidInput);
  EXPECT_THROW(caster.occluded(Vec3::Zero(), Vec3(1, 0, 0), -1.0), InvalidInput);
  EXPECT_EQ(caster.mesh().num_faces(), 80);
}

}  // namespace
}  // namespace breastfit::spatial
