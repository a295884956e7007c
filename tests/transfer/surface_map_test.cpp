#include "breastfit/transfer/surface_map.h"

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"
#include "breastfit/model/pose_evaluator.h"
#include "support/toy_model.h"

namespace breastfit::transfer {
namespace {

const model::RiggedModel& toy() {
  static const model::RiggedModel m = test::make_toy_model();
  return m;
}

TriangleMesh posed(std::uint64_t seed) {
  TriangleMesh m;
  m.V = model::pose_vertices(toy(), test::random_toy_pose(toy(), seed, 0.6));
  m.F = toy().rest.F;
  return m;
}

Markups drawings_on(const TriangleMesh& fit) {
  Markups m;
  for (const auto& lm : toy().landmarks) m.points.push_back({lm.name, lm.point.position(fit.V, fit.F)});
  for (const auto& d : toy().drawings) {
    Curve c{d.name, d.closed, Points(static_cast<Eigen::Index>(d.points.size()), 3)};
    for (size_t i = 0; i < d.points.size(); ++i) c.points.row(static_cast<Eigen::Index>(i)) = d.points[i].position(fit.V, fit.F).transpose();
    m.curves.push_back(c);
  }
  return m;
}

double max_diff(const Markups& a, const Markups& b) {
  double d = 0;
  EXPECT_EQ(a.points.size(), b.points.size());
  EXPECT_EQ(a.curves.size(), b.curves.size());
  for (size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].name, b.points[i].name);
    d = std::max(d, (a.points[i].position - b.points[i].position).norm());
  }
  for (size_t i = 0; i < a.curves.size(); ++i) {
    EXPECT_EQ(a.curves[i].name, b.curves[i].name);
    EXPECT_EQ(a.curves[i].closed, b.curves[i].closed);
    EXPECT_EQ(a.curves[i].points.rows(), b.curves[i].points.rows());
    d = std::max(d, (a.curves[i].points - b.curves[i].points).rowwise().norm().maxCoeff());
  }
  return d;
}

TEST(SurfaceMap, FromAFitToItselfIsTheIdentity) {
  const TriangleMesh a = posed(1);
  const Markups in = drawings_on(a);
  const MapResult r = map_markups(in, a, a, nullptr);
  EXPECT_LT(max_diff(r.markups, in), 1e-9);
  for (const auto& p : r.points) {
    EXPECT_LT(p.distance_to_fit_a_mm, 1e-9);
    EXPECT_EQ(p.confidence, "high");
    EXPECT_FALSE(p.projected);
  }
}

TEST(SurfaceMap, CarriesSurfacePointsToTheOtherPose) {
  const TriangleMesh a = posed(2), b = posed(3);
  const Markups on_a = drawings_on(a), on_b = drawings_on(b);
  ASSERT_GT(max_diff(on_a, on_b), 5.0);  // the poses really differ
  const MapResult r = map_markups(on_a, a, b, nullptr);
  EXPECT_LT(max_diff(r.markups, on_b), 1e-6);
}

TEST(SurfaceMap, ConfidenceFallsWithTheDistanceToFitA) {
  const TriangleMesh a = posed(4), b = posed(5);
  const SurfaceMap map(a, b);
  const Vec3 on = toy().landmarks[0].point.position(a.V, a.F);
  // push the point off the surface along the mesh normal at the landmark
  const auto& f = toy().rest.F.row(toy().landmarks[0].point.face);
  const Vec3 n = (a.V.row(f(1)) - a.V.row(f(0))).cross(a.V.row(f(2)) - a.V.row(f(0))).normalized().transpose();
  Markups in;
  in.points = {{"near", on + 2.0 * n}, {"mid", on + 6.0 * n}, {"far", on + 25.0 * n}};
  const MapResult r = map_markups(in, a, b, nullptr);
  ASSERT_EQ(r.points.size(), 3u);
  EXPECT_NEAR(r.points[0].distance_to_fit_a_mm, 2.0, 0.2);
  EXPECT_EQ(r.points[0].confidence, "high");
  EXPECT_EQ(r.points[1].confidence, "medium");
  EXPECT_EQ(r.points[2].confidence, "low");
  EXPECT_EQ(r.count("low"), 1);
  // near the landmark the mapped point is B's landmark
  EXPECT_LT((r.points[0].output - toy().landmarks[0].point.position(b.V, b.F)).norm(), 3.0);
}

TEST(SurfaceMap, ProjectsOntoScanBWhereItExists) {
  const TriangleMesh a = posed(6), b = posed(7);
  // scan B: fitted B pushed 2 mm outwards, with the triangles of the lower half removed
  TriangleMesh scan;
  scan.F = b.F;
  scan.V = b.V;
  Points N = Points::Zero(b.V.rows(), 3);
  for (Index f = 0; f < b.num_faces(); ++f) {
    const Vec3 fn = (b.V.row(b.F(f, 1)) - b.V.row(b.F(f, 0))).cross(b.V.row(b.F(f, 2)) - b.V.row(b.F(f, 0))).transpose();
    for (int k = 0; k < 3; ++k) N.row(b.F(f, k)) += fn.transpose();
  }
  for (Index v = 0; v < b.num_vertices(); ++v) scan.V.row(v) += 2.0 * N.row(v).normalized();
  const fit::ScanTarget target(scan, 0);
  const Markups in = drawings_on(a);
  const MapResult r = map_markups(in, a, b, &target);
  int supported = 0;
  for (const auto& p : r.points) {
    EXPECT_TRUE(p.projected);
    if (p.supported_by_scan_b) {
      ++supported;
      EXPECT_NEAR(p.scan_b_offset_mm, 2.0, 0.5);
    }
  }
  EXPECT_GT(supported, static_cast<int>(r.points.size()) / 2);
  MapOptions bad;
  bad.medium_confidence_mm = 1.0;
  EXPECT_THROW(map_markups(in, a, b, nullptr, bad), InvalidInput);
  TriangleMesh other = b;
  other.F.row(0).reverseInPlace();
  EXPECT_THROW(map_markups(in, a, other, nullptr), InvalidInput);
}

}  // namespace
}  // namespace breastfit::transfer
