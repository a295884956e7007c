#include "breastfit/spatial/closest_point_index.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/core/rng.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/spatial/point_triangle.h"
#include "spatial/spatial_test_meshes.h"

namespace breastfit::spatial {
namespace {

namespace meshes = breastfit::test::spatial_meshes;

struct Brute {
  double sq_dist = std::numeric_limits<double>::infinity();
  Index face = -1;
  double second = std::numeric_limits<double>::infinity();  // best over the other faces
};

/// Every face, lowest (sq_dist, face) wins.
Brute brute_force(const TriangleMesh& m, const Vec3& q) {
  Brute b;
  for (Index f = 0; f < m.num_faces(); ++f) {
    const PointTriangleResult r = closest_point_on_triangle(
        q, m.V.row(m.F(f, 0)).transpose(), m.V.row(m.F(f, 1)).transpose(),
        m.V.row(m.F(f, 2)).transpose());
    if (r.sq_dist < b.sq_dist) {
      b.second = b.sq_dist;
      b.sq_dist = r.sq_dist;
      b.face = f;
    } else {
      b.second = std::min(b.second, r.sq_dist);
    }
  }
  return b;
}

std::vector<Vec3> queries(const TriangleMesh& m, int n, double near_dist, double far_box,
                          std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Vec3> q;
  const Vec3 lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  const Vec3 mid = 0.5 * (lo + hi);
  const double ext = (hi - lo).maxCoeff();
  for (int i = 0; i < n; ++i) {
    if (i % 3 == 2) {  // far: anywhere in a box `far_box` times the mesh size
      q.push_back(mid + far_box * ext *
                            Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)));
    } else {  // near: a surface point pushed off by up to near_dist
      q.push_back(meshes::random_surface_point(m, rng) +
                  rng.uniform(0, near_dist) * meshes::random_unit(rng));
    }
  }
  return q;
}

void expect_matches_brute_force(const TriangleMesh& m, const std::vector<Vec3>& qs) {
  const ClosestPointIndex index(m);
  int unique = 0;
  for (std::size_t i = 0; i < qs.size(); ++i) {
    const Vec3& q = qs[i];
    const Brute b = brute_force(m, q);
    const ClosestPoint cp = index.closest(q);
    ASSERT_NEAR(cp.sq_dist, b.sq_dist, 1e-9 * b.sq_dist + 1e-300) << "query " << i;
    // The index evaluates each triangle exactly like the brute force and breaks ties by the
    // lowest face, so even the face of a tie must agree.
    ASSERT_EQ(cp.face, b.face) << "query " << i;
    if (b.second > b.sq_dist * (1 + 1e-9)) ++unique;
    // The point is rebuilt from barycentrics: rounding grows with the coordinates' size.
    const double round_off = 1e-14 * q.cwiseAbs().maxCoeff() * (cp.distance() + 1e-3);
    EXPECT_NEAR((cp.point - q).squaredNorm(), cp.sq_dist, 1e-9 * cp.sq_dist + 1e-12 + round_off);
    const Vec3 x = cp.bary[0] * m.V.row(m.F(cp.face, 0)).transpose() +
                   cp.bary[1] * m.V.row(m.F(cp.face, 1)).transpose() +
                   cp.bary[2] * m.V.row(m.F(cp.face, 2)).transpose();
    EXPECT_LT((x - cp.point).norm(), 1e-9);
    EXPECT_NEAR(cp.distance(), std::sqrt(b.sq_dist), 1e-9 * std::sqrt(b.sq_dist) + 1e-300);
  }
  EXPECT_GT(unique, static_cast<int>(qs.size()) / 2);  // the face check was not all ties
}

TEST(ClosestPointIndex, MatchesBruteForceOnRandomSoup) {
  const TriangleMesh m = meshes::random_soup(2000, 100.0, 5.0, 1);
  expect_matches_brute_force(m, queries(m, 1500, 3.0, 2.0, 2));
}

TEST(ClosestPointIndex, MatchesBruteForceOnSphere) {
  const TriangleMesh m = meshes::icosphere(4, 120.0, Vec3(10, -20, 30));
  expect_matches_brute_force(m, queries(m, 1500, 5.0, 3.0, 3));
  // The centre is equidistant from every vertex: ties resolved identically.
  const ClosestPointIndex index(m);
  EXPECT_EQ(index.closest(Vec3(10, -20, 30)).face, brute_force(m, Vec3(10, -20, 30)).face);
}

TEST(ClosestPointIndex, MatchesBruteForceOnNoisySheetWithHoles) {
  const TriangleMesh m = meshes::noisy_sheet(40, 2.5, 0.8, 0.15, 4);
  expect_matches_brute_force(m, queries(m, 1500, 4.0, 1.5, 5));
}

TEST(ClosestPointIndex, LargeCoordinatesAndTinyTriangles) {
  // Far from the origin, so float boxes round coarsely compared with the triangles.
  TriangleMesh m = meshes::random_soup(500, 1.0, 0.01, 6);
  m.V.rowwise() += Eigen::RowVector3d(1e5, -2e5, 3e5);
  expect_matches_brute_force(m, queries(m, 600, 0.02, 2.0, 7));
}

TEST(ClosestPointIndex, DegenerateTrianglesInTheMesh) {
  TriangleMesh m = meshes::noisy_sheet(10, 1.0, 0.3, 0.0, 8);
  // Append collinear, coincident and single-point triangles.
  const Index nv = m.num_vertices();
  m.V.conservativeResize(nv + 4, 3);
  m.V.row(nv) << 2, 2, 1;
  m.V.row(nv + 1) << 4, 4, 1;
  m.V.row(nv + 2) << 6, 6, 1;
  m.V.row(nv + 3) << 5, 1, -1;
  const Index nf = m.num_faces();
  m.F.conservativeResize(nf + 3, 3);
  m.F.row(nf) << nv, nv + 1, nv + 2;      // collinear
  m.F.row(nf + 1) << nv + 3, nv + 3, nv;  // two coincident corners
  m.F.row(nf + 2) << nv + 3, nv + 3, nv + 3;  // a point
  Rng rng(9);
  std::vector<Vec3> qs = queries(m, 500, 2.0, 1.5, 10);
  for (int i = 0; i < 200; ++i) {
    qs.push_back(Vec3(3, 3, 1) + rng.uniform(0, 3) * meshes::random_unit(rng));
    qs.push_back(Vec3(5, 1, -1) + rng.uniform(0, 1) * meshes::random_unit(rng));
  }
  expect_matches_brute_force(m, qs);
  const ClosestPointIndex index(m);
  const ClosestPoint cp = index.closest(Vec3(5, 1, -1.01));
  EXPECT_TRUE(cp.point.allFinite());
  EXPECT_NEAR(cp.sq_dist, 1e-4, 1e-12);
  EXPECT_EQ(index.face_normal(nf), Vec3::Zero());
}

TEST(ClosestPointIndex, BoundaryFlagsOnAnOpenSheet) {
  // Flat 10×10 sheet, 1 mm cells, z = 0.
  const TriangleMesh m = meshes::noisy_sheet(10, 1.0, 0.0, 0.0, 1);
  const ClosestPointIndex index(m);
  // Above the interior: a face, never boundary.
  ClosestPoint cp = index.closest(Vec3(3.3, 4.6, 2.0));
  EXPECT_EQ(cp.feature, ClosestFeature::Face);
  EXPECT_FALSE(cp.on_boundary);
  EXPECT_NEAR(cp.sq_dist, 4.0, 1e-12);
  // Above the interior on a face touching the boundary: still a face, not boundary.
  cp = index.closest(Vec3(0.2, 5.5, 1.0));
  EXPECT_EQ(cp.feature, ClosestFeature::Face);
  EXPECT_FALSE(cp.on_boundary);
  // Beyond the x = 0 border: an edge of the border.
  cp = index.closest(Vec3(-1.0, 5.5, 0.5));
  EXPECT_TRUE(cp.feature == ClosestFeature::Edge01 || cp.feature == ClosestFeature::Edge12 ||
              cp.feature == ClosestFeature::Edge20);
  EXPECT_TRUE(cp.on_boundary);
  EXPECT_NEAR(cp.point.x(), 0.0, 1e-12);
  // Beyond the corner: the corner vertex.
  cp = index.closest(Vec3(-1.0, -2.0, 0.3));
  EXPECT_TRUE(is_vertex_feature(cp.feature));
  EXPECT_TRUE(cp.on_boundary);
  EXPECT_LT(cp.point.norm(), 1e-12);
  // A border vertex seen from outside across the border (x = 10 side, at y = 5).
  cp = index.closest(Vec3(11.0, 5.0, 0.0));
  EXPECT_TRUE(is_vertex_feature(cp.feature));
  EXPECT_TRUE(cp.on_boundary);
  // An interior vertex approached from below its plane at a distance: vertex or face, never
  // boundary.
  cp = index.closest(Vec3(5.0, 5.0, -3.0));
  EXPECT_FALSE(cp.on_boundary);
  // Beyond the interior edge of a hole: make one and query over its middle.
  TriangleMesh holed = m;
  std::vector<int> keep;
  for (Index f = 0; f < m.num_faces(); ++f) {
    if (f != 2 * (5 * 10 + 5) && f != 2 * (5 * 10 + 5) + 1) keep.push_back(f);  // cell (5, 5)
  }
  holed.F = m.F(keep, Eigen::all);
  const ClosestPointIndex holed_index(holed);
  cp = holed_index.closest(Vec3(5.5, 5.5, 0.1));
  EXPECT_TRUE(cp.on_boundary);
  EXPECT_FALSE(cp.feature == ClosestFeature::Face);
  cp = holed_index.closest(Vec3(2.5, 2.5, 0.1));
  EXPECT_FALSE(cp.on_boundary);
}

TEST(ClosestPointIndex, ClosedSphereHasNoBoundary) {
  const TriangleMesh m = meshes::icosphere(3, 50.0);
  const ClosestPointIndex index(m);
  Rng rng(12);
  for (int i = 0; i < 500; ++i) {
    const Vec3 q = rng.uniform(0, 100) * meshes::random_unit(rng);
    EXPECT_FALSE(index.closest(q).on_boundary);
  }
}

TEST(ClosestPointIndex, NonManifoldEdgeIsNotBoundary) {
  // Three fins at 0°, 30° and 60° around the z axis share the edge (0, 1): it has three faces,
  // so it is not an open-boundary edge.
  const double c30 = std::cos(M_PI / 6), s30 = 0.5;
  const TriangleMesh m = meshes::make_mesh(
      {{0, 0, 0}, {0, 0, 1}, {1, 0, 0.5}, {c30, s30, 0.5}, {s30, c30, 0.5}},
      {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  const ClosestPointIndex index(m);
  // From the opposite side (210°) the shared edge is closest.
  const ClosestPoint cp = index.closest(Vec3(-0.6 * c30, -0.3, 0.5));
  EXPECT_TRUE(is_edge_feature(cp.feature));
  EXPECT_NEAR(cp.point.x(), 0.0, 1e-12);
  EXPECT_NEAR(cp.point.y(), 0.0, 1e-12);
  EXPECT_NEAR(cp.point.z(), 0.5, 1e-12);
  EXPECT_FALSE(cp.on_boundary);
  // The outer edge 1–2 of the first fin is open.
  const ClosestPoint outer = index.closest(Vec3(1.0, 0.0, 1.5));
  EXPECT_EQ(outer.face, 0);
  EXPECT_EQ(outer.feature, ClosestFeature::Edge12);
  EXPECT_TRUE(outer.on_boundary);
}

TEST(ClosestPointIndex, ClosestWithinAgreesWithClosest) {
  const TriangleMesh m = meshes::noisy_sheet(30, 2.0, 1.0, 0.1, 13);
  const ClosestPointIndex index(m);
  const std::vector<Vec3> qs = queries(m, 2000, 6.0, 1.0, 14);
  int found = 0, missed = 0;
  for (const Vec3& q : qs) {
    const ClosestPoint cp = index.closest(q);
    for (const double r : {0.5, 2.0, 10.0}) {
      const std::optional<ClosestPoint> w = index.closest_within(q, r);
      if (cp.distance() <= r * (1 - 1e-12)) {
        ASSERT_TRUE(w.has_value());
        EXPECT_EQ(w->face, cp.face);
        EXPECT_EQ(w->sq_dist, cp.sq_dist);
        EXPECT_EQ(w->feature, cp.feature);
        EXPECT_EQ(w->on_boundary, cp.on_boundary);
        ++found;
      } else if (cp.distance() > r * (1 + 1e-12)) {
        EXPECT_FALSE(w.has_value());
        ++missed;
      }
    }
  }
  EXPECT_GT(found, 1000);
  EXPECT_GT(missed, 1000);
  EXPECT_THROW(index.closest_within(qs[0], -1.0), InvalidInput);
  // Radius zero: only a query exactly on the surface finds something.
  EXPECT_TRUE(index.closest_within(m.V.row(m.F(0, 0)).transpose(), 0.0).has_value());
}

TEST(ClosestPointIndex, HintsAndBatchGiveIdenticalResults) {
  const TriangleMesh m = meshes::icosphere(4, 80.0);
  const ClosestPointIndex index(m);
  const std::vector<Vec3> qs = queries(m, 1000, 5.0, 2.0, 15);
  Points Q(static_cast<Index>(qs.size()), 3);
  for (std::size_t i = 0; i < qs.size(); ++i) Q.row(static_cast<Index>(i)) = qs[i];
  const std::vector<ClosestPoint> batch = index.closest_batch(Q);
  ASSERT_EQ(batch.size(), qs.size());
  Rng rng(16);
  for (std::size_t i = 0; i < qs.size(); ++i) {
    const ClosestPoint cp = index.closest(qs[i]);
    const auto hint = static_cast<Index>(rng.below(static_cast<std::uint64_t>(m.num_faces())));
    for (const ClosestPoint& other :
         {index.closest(qs[i], hint), index.closest(qs[i], cp.face), index.closest(qs[i], -5),
          batch[i]}) {
      EXPECT_EQ(other.face, cp.face);
      EXPECT_EQ(other.sq_dist, cp.sq_dist);
      EXPECT_EQ(other.feature, cp.feature);
      EXPECT_EQ(other.point, cp.point);
    }
    const auto w = index.closest_within(qs[i], 3.0, hint);
    EXPECT_EQ(w.has_value(), cp.distance() <= 3.0);
    if (w) {
      EXPECT_EQ(w->face, cp.face);
    }
  }
  EXPECT_TRUE(index.closest_batch(Points(0, 3)).empty());
}

TEST(ClosestPointIndex, QueryOrderIsAPermutationAlongAZCurve) {
  // Points on a 16×16 grid in the plane z = 0, given row by row: the Z curve visits each 2×2
  // block of cells before the next, so consecutive queries are neighbours far more often.
  Points Q(256, 3);
  for (int r = 0; r < 256; ++r) Q.row(r) = Vec3(r % 16, r / 16, 0.0).transpose();
  const std::vector<std::uint32_t> order = query_order(Q);
  ASSERT_EQ(order.size(), 256u);
  std::vector<int> seen(256, 0);
  for (const std::uint32_t i : order) ++seen[i];
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), 256);
  EXPECT_EQ(order[0], 0u);  // the low corner first
  EXPECT_EQ(order[1], 1u);  // then its neighbour along x (bit 0 of the code)
  EXPECT_EQ(order[2], 16u);  // then the one above it
  // Each run of 16 consecutive queries spans a small block (row by row: a whole row, 15 wide).
  double span = 0;
  for (std::size_t b = 0; b < order.size(); b += 16) {
    Eigen::RowVector3d lo = Q.row(order[b]), hi = lo;
    for (std::size_t k = b; k < b + 16; ++k) {
      lo = lo.cwiseMin(Q.row(order[k]));
      hi = hi.cwiseMax(Q.row(order[k]));
    }
    span += (hi - lo).norm() / 16.0;
  }
  EXPECT_LT(span, 7.5) << "mean diagonal of 16 consecutive queries";
  // Equal points keep their row order; empty and single inputs; a non-finite row is refused.
  Points same = Points::Constant(3, 3, 2.0);
  EXPECT_EQ(query_order(same), (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_TRUE(query_order(Points(0, 3)).empty());
  Q(7, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(query_order(Q), InvalidInput);
}

TEST(ClosestPointIndex, KeepsTheVertexNormalsOfItsMesh) {
  const TriangleMesh m = meshes::noisy_sheet(30, 10.0, 0.4, 0.1, 21);
  const ClosestPointIndex index(m, 2);
  EXPECT_EQ(index.vertex_normals(), mesh::vertex_normals(m));
}

TEST(ClosestPointIndex, SmoothAndFaceNormalsOnASphere) {
  const TriangleMesh m = meshes::icosphere(4, 100.0);
  const ClosestPointIndex index(m);
  Rng rng(17);
  double max_smooth_angle = 0, max_face_angle = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 dir = meshes::random_unit(rng);
    const ClosestPoint cp = index.closest(rng.uniform(90, 110) * dir);
    const Vec3 radial = cp.point.normalized();
    const Vec3 ns = index.smooth_normal(cp), nf = index.face_normal(cp.face);
    EXPECT_NEAR(ns.norm(), 1.0, 1e-12);
    EXPECT_NEAR(nf.norm(), 1.0, 1e-12);
    max_smooth_angle = std::max(max_smooth_angle, std::acos(std::min(1.0, ns.dot(radial))));
    max_face_angle = std::max(max_face_angle, std::acos(std::min(1.0, nf.dot(radial))));
  }
  // Outward normals; the interpolated normal follows the sphere better than the flat one.
  EXPECT_LT(max_smooth_angle, 0.02);
  EXPECT_LT(max_face_angle, 0.06);
  EXPECT_LT(max_smooth_angle, max_face_angle);
  // At a vertex the smooth normal is that vertex's normal: radial on a sphere.
  ClosestPoint at_vertex;
  at_vertex.face = 0;
  at_vertex.bary = Vec3(1, 0, 0);
  const Vec3 v0 = m.V.row(m.F(0, 0)).transpose();
  EXPECT_GT(index.smooth_normal(at_vertex).dot(v0.normalized()), 1 - 1e-6);
  EXPECT_THROW(index.face_normal(m.num_faces()), InvalidInput);
  EXPECT_THROW(index.face_normal(-1), InvalidInput);
}

TEST(ClosestPointIndex, RejectsBadMeshesAndQueries) {
  TriangleMesh empty;
  empty.V = Points::Random(5, 3);
  EXPECT_THROW(ClosestPointIndex{empty}, InvalidInput);
  TriangleMesh nan_mesh = meshes::icosphere(1, 1.0);
  nan_mesh.V(3, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ClosestPointIndex{nan_mesh}, InvalidInput);
  TriangleMesh inf_mesh = meshes::icosphere(1, 1.0);
  inf_mesh.V(0, 0) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ClosestPointIndex{inf_mesh}, InvalidInput);
  TriangleMesh bad_index = meshes::icosphere(1, 1.0);
  bad_index.F(2, 1) = bad_index.num_vertices();
  EXPECT_THROW(ClosestPointIndex{bad_index}, InvalidInput);
  const ClosestPointIndex index(meshes::icosphere(1, 1.0));
  EXPECT_THROW(index.closest(Vec3(0, std::nan(""), 0)), InvalidInput);
}

TEST(ClosestPointIndex, OwnsACopyOfTheMeshAndMoves) {
  TriangleMesh m = meshes::icosphere(2, 10.0);
  ClosestPointIndex index(m);
  const Vec3 q(0, 0, 20);
  const ClosestPoint before = index.closest(q);
  m.V *= 2.0;  // the caller's mesh changes: the index must not
  EXPECT_EQ(index.closest(q).sq_dist, before.sq_dist);
  EXPECT_TRUE((index.mesh().V * 2.0).isApprox(m.V));
  EXPECT_EQ(index.mesh().F, m.F);
  ClosestPointIndex moved(std::move(index));
  EXPECT_EQ(moved.closest(q).face, before.face);
  ClosestPointIndex other(meshes::icosphere(1, 1.0));
  other = std::move(moved);
  EXPECT_EQ(other.closest(q).face, before.face);
}

/// Every field of the two indices' answers to `qs` is the same bits.
void expect_same_answers(const ClosestPointIndex& x, const ClosestPointIndex& y, const std::vector<Vec3>& qs) {
  for (const Vec3& q : qs) {
    const ClosestPoint a = x.closest(q), b = y.closest(q);
    ASSERT_EQ(a.face, b.face);
    ASSERT_EQ(a.sq_dist, b.sq_dist);
    ASSERT_EQ(a.point, b.point);
    ASSERT_EQ(a.bary, b.bary);
    ASSERT_EQ(a.feature, b.feature);
    ASSERT_EQ(a.on_boundary, b.on_boundary);
    ASSERT_EQ(x.smooth_normal(a), y.smooth_normal(b));
  }
}

TEST(ClosestPointIndex, TakingOverTheMeshGivesTheSameIndex) {
  const TriangleMesh m = meshes::noisy_sheet(30, 2.0, 1.0, 0.1, 21);
  const ClosestPointIndex copied(m);
  TriangleMesh tmp = m;
  const ClosestPointIndex taken(std::move(tmp));
  EXPECT_EQ(taken.mesh().V, m.V);
  EXPECT_EQ(taken.mesh().F, m.F);
  expect_same_answers(copied, taken, queries(m, 2000, 4.0, 1.5, 22));
}

/// Every query's answer of `moved` (an index moved to m's positions) against a new index over m,
/// with and without a radius and a hint, and the normals and mesh it keeps.
void expect_moved_like_new(const ClosestPointIndex& moved, const TriangleMesh& m, std::uint64_t seed) {
  const ClosestPointIndex fresh(m);
  EXPECT_EQ(moved.mesh().V, m.V);
  EXPECT_EQ(moved.vertex_normals(), fresh.vertex_normals());
  for (Index f = 0; f < m.num_faces(); f += 7) EXPECT_EQ(moved.face_normal(f), fresh.face_normal(f));
  const std::vector<Vec3> qs = queries(m, 1500, 4.0, 1.2, seed);
  expect_same_answers(moved, fresh, qs);
  for (std::size_t i = 0; i < qs.size(); ++i) {
    const auto a = moved.closest_within(qs[i], 2.0, static_cast<Index>(i) % m.num_faces());
    const auto b = fresh.closest_within(qs[i], 2.0);
    ASSERT_EQ(a.has_value(), b.has_value());
    if (a) EXPECT_EQ(a->face, b->face);
  }
}

// move_vertices keeps the tree and refits it: the answers are those of an index built over the
// moved mesh — bent a little, turned far (boxes much looser than a new tree's), a triangle made
// degenerate and one made whole again, corners stored as floats kept as floats when the new ones
// are floats and built anew when not; bad positions are refused and leave the index as it was.
TEST(ClosestPointIndex, MovedVerticesGiveTheAnswersOfANewIndex) {
  TriangleMesh m = meshes::noisy_sheet(40, 2.5, 0.8, 0.15, 51);
  ClosestPointIndex index(m);
  const Points rest = m.V;
  // Bent by a smooth field of a few millimetres.
  for (Index i = 0; i < m.V.rows(); ++i)
    m.V.row(i) += 2.5 * Vec3(std::sin(0.1 * rest(i, 1)), std::cos(0.07 * rest(i, 0)), std::sin(0.05 * rest(i, 0))).transpose();
  index.move_vertices(m.V);
  expect_moved_like_new(index, m, 52);
  // Turned by 90° about the sheet's middle and lifted: every box far from where the tree was built.
  const Vec3 mid = rest.colwise().mean().transpose();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(M_PI / 2, Vec3(1, 1, 0).normalized()).toRotationMatrix();
  for (Index i = 0; i < m.V.rows(); ++i) m.V.row(i) = (turn * (rest.row(i).transpose() - mid) + mid + Vec3(0, 0, 30)).transpose();
  index.move_vertices(m.V);
  expect_moved_like_new(index, m, 53);
  // Face 0 collapsed onto its first corner (degenerate), then back.
  const Points before = m.V;
  m.V.row(m.F(0, 1)) = m.V.row(m.F(0, 0));
  m.V.row(m.F(0, 2)) = m.V.row(m.F(0, 0));
  index.move_vertices(m.V);
  EXPECT_EQ(index.face_normal(0), Vec3::Zero());
  expect_moved_like_new(index, m, 54);
  m.V = before;
  index.move_vertices(m.V);
  EXPECT_NE(index.face_normal(0), Vec3::Zero());
  expect_moved_like_new(index, m, 55);
  // With the normals given (the caller's mesh::vertex_normals): the same.
  m.V = rest;
  index.move_vertices(m.V, mesh::vertex_normals(m));
  expect_moved_like_new(index, m, 60);
  // Refused: the wrong number of positions or normals, a NaN. The index still answers for the
  // last positions.
  EXPECT_THROW(index.move_vertices(m.V.topRows(m.V.rows() - 1)), InvalidInput);
  EXPECT_THROW(index.move_vertices(m.V, m.V.topRows(3)), InvalidInput);
  Points bad = m.V;
  bad(3, 1) = std::nan("");
  EXPECT_THROW(index.move_vertices(bad), InvalidInput);
  EXPECT_THROW(index.move_vertices(m.V, bad), InvalidInput);
  expect_moved_like_new(index, m, 56);

  // Corners that are floats: leaves stored in floats. Moved to other floats they stay so; moved
  // to positions that are not floats, the index is built anew; either way the answers are exact.
  TriangleMesh f = meshes::noisy_sheet(30, 2.0, 0.5, 0.1, 57);
  f.V = f.V.cast<float>().cast<double>();
  ClosestPointIndex floats(f);
  f.V *= 2.0;  // still floats (doubled exactly), all moved
  ASSERT_EQ(f.V.cast<float>().cast<double>(), f.V);
  floats.move_vertices(f.V);
  expect_moved_like_new(floats, f, 58);
  f.V.array() += 1e-9;  // no longer floats
  floats.move_vertices(f.V);
  expect_moved_like_new(floats, f, 59);
}

TEST(ClosestPointIndex, SameIndexWhateverTheThreadsOfTheBuild) {
  // Large enough for several chunks of every parallel loop of the build (faces, subtrees,
  // leaves), with an open border and holes.
  const TriangleMesh m = meshes::noisy_sheet(220, 1.0, 0.4, 0.05, 31);
  ASSERT_GT(m.num_faces(), 80000);
  const ClosestPointIndex serial(m);
  const std::vector<Vec3> qs = queries(m, 3000, 3.0, 1.0, 32);
  for (const int threads : {2, 3}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    expect_same_answers(serial, ClosestPointIndex(m, threads), qs);
  }
}

TEST(ClosestPointIndex, CornersThatAreFloatsGiveTheSameAnswers) {
  // A leaf whose corners are all exactly floats (scans stored in float) keeps them as floats,
  // half the bytes: the answers must not change. Every vertex rounded to float, then only those
  // of one half of the sheet (leaves of both kinds side by side).
  const TriangleMesh m = meshes::noisy_sheet(40, 2.5, 0.8, 0.15, 4);
  TriangleMesh rounded = m;
  rounded.V = m.V.cast<float>().cast<double>();
  ASSERT_NE(rounded.V, m.V);
  expect_matches_brute_force(rounded, queries(rounded, 1500, 4.0, 1.5, 41));
  TriangleMesh half = m;
  const double mid = 0.5 * (m.V.col(0).minCoeff() + m.V.col(0).maxCoeff());
  for (Index i = 0; i < m.V.rows(); ++i) {
    if (m.V(i, 0) < mid) half.V.row(i) = rounded.V.row(i);
  }
  expect_matches_brute_force(half, queries(half, 1500, 4.0, 1.5, 42));
  // The parallel build sizes the blocks in a separate pass: the same index with more threads.
  TriangleMesh big = meshes::noisy_sheet(220, 1.0, 0.4, 0.05, 31);
  big.V = big.V.cast<float>().cast<double>();
  expect_same_answers(ClosestPointIndex(big), ClosestPointIndex(big, 2), queries(big, 3000, 3.0, 1.0, 43));
}

/// The vertices used by a triangle of m within `radius` of q, by index (the brute force of
/// vertices_within, with the same squared distance).
std::vector<Index> brute_vertices_within(const TriangleMesh& m, const Vec3& q, double radius) {
  std::vector<bool> used(static_cast<std::size_t>(m.num_vertices()), false);
  for (Index f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(m.F(f, k))] = true;
  std::vector<Index> out;
  for (Index v = 0; v < m.num_vertices(); ++v) {
    double s = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double diff = m.V(v, k) - q[k];
      s += diff * diff;
    }
    if (used[static_cast<std::size_t>(v)] && s <= radius * radius) out.push_back(v);
  }
  return out;
}

TEST(ClosestPointIndex, VerticesWithinARadiusMatchBruteForce) {
  // Small balls (sorted and deduplicated) and large ones (the bitmap), on a closed sphere, an
  // open sheet with holes, float corners and a mesh with a vertex no triangle uses.
  TriangleMesh sheet = meshes::noisy_sheet(40, 2.5, 0.8, 0.15, 4);
  TriangleMesh rounded = sheet;
  rounded.V = sheet.V.cast<float>().cast<double>();
  TriangleMesh stray = meshes::icosphere(3, 50.0);
  stray.V.conservativeResize(stray.V.rows() + 1, 3);
  stray.V.row(stray.V.rows() - 1) << 0, 0, 50;  // on the sphere's pole, in no triangle
  const std::vector<TriangleMesh> ms = {meshes::icosphere(4, 120.0, Vec3(10, -20, 30)), sheet, rounded, stray};
  for (std::size_t i = 0; i < ms.size(); ++i) {
    SCOPED_TRACE("mesh " + std::to_string(i));
    const ClosestPointIndex index(ms[i]);
    const std::vector<Vec3> qs = queries(ms[i], 200, 5.0, 1.0, 50 + i);
    std::vector<Index> got;
    int nonempty = 0;
    for (std::size_t j = 0; j < qs.size(); ++j)
      for (const double r : {0.0, 2.0, 7.5, 40.0, 1e4}) {
        index.vertices_within(qs[j], r, got);
        ASSERT_EQ(got, brute_vertices_within(ms[i], qs[j], r)) << "query " << j << ", radius " << r;
        nonempty += !got.empty();
      }
    EXPECT_GT(nonempty, 400);  // not all empty (the radius 0 and far queries are)
  }
  // Inclusive: a vertex exactly at the radius is in, and a query on a vertex finds it at 0.
  const TriangleMesh& sphere = ms[0];
  const ClosestPointIndex index(sphere);
  std::vector<Index> got;
  const Vec3 v0 = sphere.V.row(0).transpose();
  index.vertices_within(v0, 0.0, got);
  EXPECT_EQ(got, std::vector<Index>{0});
  index.vertices_within(Vec3(10, -20, 30), 120.0, got);  // the centre: every vertex at 120 (± rounding)
  EXPECT_EQ(got, brute_vertices_within(sphere, Vec3(10, -20, 30), 120.0));
  EXPECT_THROW(index.vertices_within(v0, -1.0, got), InvalidInput);
  EXPECT_THROW(index.vertices_within(v0, std::numeric_limits<double>::infinity(), got), InvalidInput);
  EXPECT_THROW(index.vertices_within(Vec3(0, std::nan(""), 0), 1.0, got), InvalidInput);
}

TEST(ClosestPointIndex, ConcurrentQueriesAgree) {
  const TriangleMesh m = meshes::icosphere(4, 100.0);
  const ClosestPointIndex index(m);
  const std::vector<Vec3> qs = queries(m, 4000, 5.0, 2.0, 18);
  std::vector<Index> serial(qs.size()), a(qs.size()), b(qs.size());
  for (std::size_t i = 0; i < qs.size(); ++i) serial[i] = index.closest(qs[i]).face;
  std::thread t1([&] {
    for (std::size_t i = 0; i < qs.size(); ++i) a[i] = index.closest(qs[i]).face;
  });
  std::thread t2([&] {
    for (std::size_t i = qs.size(); i-- > 0;) b[i] = index.closest(qs[i]).face;
  });
  t1.join();
  t2.join();
  EXPECT_EQ(a, serial);
  EXPECT_EQ(b, serial);
}

}  // namespace
}  // namespace breastfit::spatial
