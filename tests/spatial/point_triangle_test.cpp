#include "breastfit/spatial/point_triangle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "breastfit/core/rng.h"
#include "spatial/spatial_test_meshes.h"

namespace breastfit::spatial {
namespace {

namespace meshes = breastfit::test::spatial_meshes;

using LVec = Eigen::Matrix<long double, 3, 1>;

long double ref_segment_sq(const LVec& p, const LVec& x, const LVec& y) {
  const LVec d = y - x;
  const long double dd = d.squaredNorm();
  long double t = dd > 0 ? (p - x).dot(d) / dd : 0;
  t = std::clamp<long double>(t, 0, 1);
  return (p - x - t * d).squaredNorm();
}

/// Independent reference: plane projection (solved in long double) when it falls inside the
/// triangle, else the closest of the three edges.
long double reference_sq_dist(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const LVec P = p.cast<long double>(), A = a.cast<long double>(), B = b.cast<long double>(),
             C = c.cast<long double>();
  const LVec e0 = B - A, e1 = C - A, ap = P - A;
  const long double a00 = e0.dot(e0), a01 = e0.dot(e1), a11 = e1.dot(e1);
  const long double det = a00 * a11 - a01 * a01;
  long double best = std::min({ref_segment_sq(P, A, B), ref_segment_sq(P, B, C),
                               ref_segment_sq(P, C, A)});
  if (det > 1e-12L * a00 * a11) {
    const long double r0 = e0.dot(ap), r1 = e1.dot(ap);
    const long double v = (a11 * r0 - a01 * r1) / det, w = (a00 * r1 - a01 * r0) / det;
    if (v >= 0 && w >= 0 && v + w <= 1) best = std::min(best, (ap - v * e0 - w * e1).squaredNorm());
  }
  return best;
}

void expect_consistent(const PointTriangleResult& r, const Vec3& p, const Vec3& a, const Vec3& b,
                       const Vec3& c) {
  ASSERT_TRUE(r.point.allFinite());
  ASSERT_TRUE(r.bary.allFinite());
  EXPECT_GE(r.bary.minCoeff(), 0.0);
  EXPECT_NEAR(r.bary.sum(), 1.0, 1e-12);
  const Vec3 x = r.bary[0] * a + r.bary[1] * b + r.bary[2] * c;
  const double scale = std::max({a.norm(), b.norm(), c.norm(), 1.0});
  EXPECT_LE((x - r.point).norm(), 1e-12 * scale);
  EXPECT_NEAR(r.sq_dist, (p - r.point).squaredNorm(), 1e-9 * std::max(r.sq_dist, 1e-9));
  switch (r.feature) {
    case ClosestFeature::Vertex0: EXPECT_EQ(r.bary, Vec3(1, 0, 0)); break;
    case ClosestFeature::Vertex1: EXPECT_EQ(r.bary, Vec3(0, 1, 0)); break;
    case ClosestFeature::Vertex2: EXPECT_EQ(r.bary, Vec3(0, 0, 1)); break;
    case ClosestFeature::Edge01: EXPECT_EQ(r.bary[2], 0.0); break;
    case ClosestFeature::Edge12: EXPECT_EQ(r.bary[0], 0.0); break;
    case ClosestFeature::Edge20: EXPECT_EQ(r.bary[1], 0.0); break;
    case ClosestFeature::Face: {
      // Interior projection: the offset is normal to the triangle's plane.
      const Vec3 off = p - r.point;
      const double tol = 1e-9 * (off.norm() + 1e-9) * scale * 4;
      EXPECT_NEAR(off.dot(b - a), 0.0, tol);
      EXPECT_NEAR(off.dot(c - a), 0.0, tol);
      break;
    }
  }
}

TEST(PointTriangle, EveryRegionOfAUnitTriangle) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  struct Case {
    Vec3 p;
    ClosestFeature feature;
    Vec3 point;
  };
  const Case cases[] = {
      {{0.2, 0.2, 1.0}, ClosestFeature::Face, {0.2, 0.2, 0}},
      {{0.5, -1.0, 0.3}, ClosestFeature::Edge01, {0.5, 0, 0}},
      {{1.0, 1.0, -0.5}, ClosestFeature::Edge12, {0.5, 0.5, 0}},
      {{-2.0, 0.25, 0.0}, ClosestFeature::Edge20, {0, 0.25, 0}},
      {{-1.0, -1.0, 2.0}, ClosestFeature::Vertex0, {0, 0, 0}},
      {{3.0, -0.5, 0.0}, ClosestFeature::Vertex1, {1, 0, 0}},
      {{-0.5, 4.0, 1.0}, ClosestFeature::Vertex2, {0, 1, 0}},
  };
  for (const Case& cs : cases) {
    const PointTriangleResult r = closest_point_on_triangle(cs.p, a, b, c);
    EXPECT_EQ(r.feature, cs.feature) << cs.p.transpose();
    EXPECT_LT((r.point - cs.point).norm(), 1e-15) << cs.p.transpose();
    EXPECT_NEAR(r.sq_dist, (cs.p - cs.point).squaredNorm(), 1e-15);
    expect_consistent(r, cs.p, a, b, c);
  }
  // A point on the face: distance zero, interior barycentrics.
  const PointTriangleResult r = closest_point_on_triangle(Vec3(0.25, 0.5, 0), a, b, c);
  EXPECT_EQ(r.feature, ClosestFeature::Face);
  EXPECT_EQ(r.sq_dist, 0.0);
  EXPECT_NEAR(r.bary[0], 0.25, 1e-15);
  EXPECT_NEAR(r.bary[1], 0.25, 1e-15);
  EXPECT_NEAR(r.bary[2], 0.5, 1e-15);
}

TEST(PointTriangle, FaceRegionBarycentrics) {
  const PointTriangleResult r =
      closest_point_on_triangle(Vec3(0.2, 0.2, 5), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  EXPECT_NEAR((r.point - Vec3(0.2, 0.2, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((r.bary - Vec3(0.6, 0.2, 0.2)).norm(), 0.0, 1e-12);
}

TEST(PointTriangle, MatchesReferenceOnRandomTriangles) {
  Rng rng(7);
  for (int i = 0; i < 20000; ++i) {
    const double s = std::pow(10.0, rng.uniform(-2, 2));
    const Vec3 off(rng.uniform(-300, 300), rng.uniform(-300, 300), rng.uniform(-300, 300));
    const Vec3 a = off + s * meshes::random_unit(rng), b = off + s * meshes::random_unit(rng),
               c = off + s * meshes::random_unit(rng);
    const Vec3 p = off + s * rng.uniform(0, 3) * meshes::random_unit(rng);
    const PointTriangleResult r = closest_point_on_triangle(p, a, b, c);
    const double ref = static_cast<double>(reference_sq_dist(p, a, b, c));
    ASSERT_NEAR(r.sq_dist, ref, 1e-9 * ref + 1e-12 * s * s) << "case " << i;
    expect_consistent(r, p, a, b, c);
  }
}

TEST(PointTriangle, RawOverloadAgreesWithVecOverload) {
  Rng rng(3);
  for (int i = 0; i < 100; ++i) {
    const Vec3 a = meshes::random_unit(rng), b = meshes::random_unit(rng), c = meshes::random_unit(rng);
    const Vec3 p = 2.0 * meshes::random_unit(rng);
    const PointTriangleResult r = closest_point_on_triangle(p, a, b, c);
    double bary[3];
    ClosestFeature f;
    const double s = closest_point_on_triangle(p.data(), a.data(), b.data(), c.data(), bary, &f);
    EXPECT_EQ(s, r.sq_dist);
    EXPECT_EQ(f, r.feature);
    EXPECT_EQ(Vec3(bary[0], bary[1], bary[2]), r.bary);
  }
}

TEST(PointTriangle, DegenerateTrianglesGiveFiniteEdgeAnswers) {
  Rng rng(11);
  for (int i = 0; i < 5000; ++i) {
    const Vec3 a = 10 * meshes::random_unit(rng), d = meshes::random_unit(rng);
    const Vec3 p = 10 * meshes::random_unit(rng) * rng.uniform(0, 2);
    Vec3 b, c;
    switch (i % 5) {
      case 0: b = a + 2 * d; c = a + 5 * d; break;     // collinear, c beyond b
      case 1: b = a + 3 * d; c = a + 1 * d; break;     // collinear, c between
      case 2: b = a; c = a + 4 * d; break;             // two coincident corners
      case 3: b = a; c = a; break;                     // a single point
      default: b = a + 4 * d; c = a + 2 * d + 1e-9 * meshes::random_unit(rng); break;  // needle
    }
    const PointTriangleResult r = closest_point_on_triangle(p, a, b, c);
    const double ref = static_cast<double>(reference_sq_dist(p, a, b, c));
    ASSERT_NEAR(r.sq_dist, ref, 1e-9 * ref + 1e-12) << "case " << i;
    expect_consistent(r, p, a, b, c);
    if (i % 5 != 4) {
      EXPECT_NE(r.feature, ClosestFeature::Face) << "case " << i;
    }
  }
  // A single point: the answer is that point, reported as vertex 0.
  const Vec3 a(1, 2, 3);
  const PointTriangleResult r = closest_point_on_triangle(Vec3(4, 6, 3), a, a, a);
  EXPECT_EQ(r.feature, ClosestFeature::Vertex0);
  EXPECT_DOUBLE_EQ(r.sq_dist, 25.0);
}

TEST(PointTriangle, NeedleTriangleFaceRegion) {
  // A thin but valid triangle: a point above its middle projects onto the face.
  const Vec3 a(0, 0, 0), b(100, 0, 0), c(50, 1e-3, 0);
  const PointTriangleResult r = closest_point_on_triangle(Vec3(50, 0.0005, 2), a, b, c);
  EXPECT_EQ(r.feature, ClosestFeature::Face);
  EXPECT_NEAR(r.sq_dist, 4.0, 1e-12);
  EXPECT_NEAR(r.point.y(), 0.0005, 1e-9);  // thin triangle: barycentrics lose ~1e-12 relative
}

TEST(PointTriangle, FeaturePredicates) {
  EXPECT_TRUE(is_vertex_feature(ClosestFeature::Vertex1));
  EXPECT_FALSE(is_vertex_feature(ClosestFeature::Edge01));
  EXPECT_TRUE(is_edge_feature(ClosestFeature::Edge20));
  EXPECT_FALSE(is_edge_feature(ClosestFeature::Face));
}

}  // namespace
}  // namespace breastfit::spatial
