#include "breastfit/spatial/point_cloud_normals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "breastfit/core/errors.h"
#include "breastfit/core/rng.h"

namespace breastfit::spatial {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Uniform samples on a sphere of radius r centred at c.
Points sphere(int n, double r, const Vec3& c, std::uint64_t seed) {
  Rng rng(seed);
  Points P(n, 3);
  for (int i = 0; i < n; ++i) {
    Vec3 d(rng.normal(), rng.normal(), rng.normal());
    P.row(i) = (c + r * d.normalized()).transpose();
  }
  return P;
}

/// A torso-like open surface: the front half of an elliptic cylinder (x = a cos t, y = -b sin t,
/// t in [0, pi], anterior = -y), height h, with noise; outward normals have y < 0 at the front.
Points front_half_cylinder(int n, double a, double b, double h, double noise, std::uint64_t seed,
                           Points* outward) {
  Rng rng(seed);
  Points P(n, 3);
  outward->resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = rng.uniform(0.05, kPi - 0.05), z = rng.uniform(0, h);
    P.row(i) << a * std::cos(t), -b * std::sin(t), z;
    P.row(i) += noise * Eigen::RowVector3d(rng.normal(), rng.normal(), rng.normal());
    outward->row(i) = Eigen::RowVector3d(std::cos(t) / a, -std::sin(t) / b, 0).normalized();
  }
  return P;
}

TEST(PointCloudNormals, SphereNormalsPointOutward) {
  const Vec3 c(100, -50, 20);
  const Points P = sphere(3000, 150.0, c, 1);
  const Points N = point_cloud_normals(P);
  ASSERT_EQ(N.rows(), P.rows());
  double worst = 1.0;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    EXPECT_NEAR(N.row(i).norm(), 1.0, 1e-9);
    const Vec3 radial = (P.row(i).transpose() - c).normalized();
    worst = std::min(worst, N.row(i).dot(radial.transpose()));
  }
  EXPECT_GT(worst, std::cos(10.0 * kPi / 180.0));
}

TEST(PointCloudNormals, FrontOnlyTorsoOrientedOutward) {
  Points truth;
  const Points P = front_half_cylinder(4000, 160.0, 110.0, 400.0, 0.5, 2, &truth);
  for (bool propagate : {true, false}) {
    PointCloudNormalsOptions opt;
    opt.propagate = propagate;
    const Points N = point_cloud_normals(P, opt);
    int wrong = 0;
    for (Eigen::Index i = 0; i < P.rows(); ++i) wrong += N.row(i).dot(truth.row(i)) < 0.5;
    if (propagate) {
      EXPECT_EQ(wrong, 0) << "propagated";
    } else {
      EXPECT_LT(wrong, P.rows() / 4) << "away from centroid";
    }
  }
}

TEST(PointCloudNormals, ViewpointOrientation) {
  Rng rng(3);
  Points P(400, 3);
  for (int i = 0; i < 400; ++i) P.row(i) << rng.uniform(-100, 100), rng.uniform(-100, 100), 0.01 * rng.normal();
  PointCloudNormalsOptions opt;
  opt.viewpoint = Vec3(0, 0, -1000);
  Points N = point_cloud_normals(P, opt);
  for (Eigen::Index i = 0; i < N.rows(); ++i) EXPECT_LT(N(i, 2), -0.99) << i;
  opt.viewpoint = Vec3(20, 30, 800);
  N = point_cloud_normals(P, opt);
  for (Eigen::Index i = 0; i < N.rows(); ++i) EXPECT_GT(N(i, 2), 0.99) << i;
}

TEST(PointCloudNormals, DegenerateNeighbourhoodGivesZeroRow) {
  Points P = Points::Zero(10, 3);  // all coincident
  const Points N = point_cloud_normals(P, {.num_neighbors = 4});
  EXPECT_EQ(N.norm(), 0.0);
  EXPECT_EQ(point_cloud_normals(Points(0, 3)).rows(), 0);
}

TEST(PointCloudNormals, InvalidInputs) {
  PointCloudNormalsOptions opt;
  opt.num_neighbors = 2;
  EXPECT_THROW(opt.validate(), InvalidInput);
  EXPECT_THROW(point_cloud_normals(sphere(20, 1, Vec3::Zero(), 4), opt), InvalidInput);
  opt = {};
  opt.viewpoint = Vec3(std::numeric_limits<double>::infinity(), 0, 0);
  EXPECT_THROW(opt.validate(), InvalidInput);
  Points P = sphere(20, 1, Vec3::Zero(), 4);
  P(3, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(point_cloud_normals(P), InvalidInput);
}

TEST(PointCloudNormals, Deterministic) {
  const Points P = sphere(500, 10.0, Vec3::Zero(), 9);
  EXPECT_EQ(point_cloud_normals(P), point_cloud_normals(P));
}

}  // namespace
}  // namespace breastfit::spatial
