// The scan's skin around a point: the vertices of the scan's pieces big enough to be the body, so
// that a floating fragment in front of a breast is not taken for its tip; a hole near the nipple
// does not cut the skin; a point cloud is kept whole.
#include "breastfit/fit/skin_around.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/fit/landmark_check.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/spatial/closest_point_index.h"
#include "support/test_shapes.h"

namespace breastfit::fit {
namespace {

const Vec3 kNipple(0, -60, 0);  // the front of a breast: a sphere of radius 60 mm

TEST(SkinAround, LeavesOutAFloatingFragmentInFrontOfTheBreast) {
  const TriangleMesh scan = test::breast_with_fragment();
  const Points N = mesh::vertex_normals(scan);
  // Over every vertex the fragment is the "tip", 25–31 mm from the nipple: a false flag at 18 mm.
  const auto everywhere = breast_tip_on_scan(scan.V, scan.V, N, kNipple);
  ASSERT_TRUE(everywhere);
  EXPECT_GT((*everywhere - kNipple).norm(), 20.0);
  // On the skin: the breast's front.
  const SkinPatch skin = skin_around(scan, N, skin_vertices(scan), kNipple, 40.0);
  for (Index i = 0; i < skin.V.rows(); ++i) EXPECT_GT((skin.V.row(i).transpose() - Vec3(0, -88, 0)).norm(), 10.0);
  const auto tip = breast_tip_on_scan(skin.V, skin.V, skin.N, kNipple);
  ASSERT_TRUE(tip);
  EXPECT_LT((*tip - kNipple).norm(), 1.0) << tip->transpose();
}

TEST(SkinAround, KeepsEveryVertexWhereNoFragmentIsNear) {
  const TriangleMesh breast = test::sphere_mesh(60.0, Vec3::Zero(), 64, 128);
  const Points N = mesh::vertex_normals(breast);
  const Vec3 centre(0, -60 * std::cos(0.3), -60 * std::sin(0.3));
  const SkinPatch skin = skin_around(breast, N, skin_vertices(breast), centre, 40.0);
  Index near = 0;
  for (Index i = 0; i < breast.V.rows(); ++i) near += (breast.V.row(i).transpose() - centre).norm() < 40.0;
  EXPECT_EQ(skin.V.rows(), near);
  EXPECT_EQ(breast_tip_on_scan(skin.V, skin.V, skin.N, centre)->transpose(),
            breast_tip_on_scan(breast.V, breast.V, N, centre)->transpose());
  for (Index i = 0; i < skin.V.rows(); ++i) EXPECT_NEAR(skin.N.row(i).dot(skin.V.row(i)) / 60.0, 1.0, 0.01);
}

// A hole around the nipple (a band 10–14 mm from it) open only towards +x, where a strip between two
// slits leads out beyond 40 mm: within 40 mm the nipple's cap is a piece of its own, smaller than the
// rest, but on the whole scan it is one piece with it. The tip stays on the cap.
TriangleMesh sphere_with_hole_around_nipple() {
  const TriangleMesh sphere = test::sphere_mesh(60.0, Vec3::Zero(), 96, 192);
  TriangleMesh holed;
  holed.V = sphere.V;
  std::vector<Eigen::Matrix<Index, 1, 3>> kept;
  for (Index f = 0; f < sphere.F.rows(); ++f) {
    const Vec3 c = (sphere.V.row(sphere.F(f, 0)) + sphere.V.row(sphere.F(f, 1)) + sphere.V.row(sphere.F(f, 2))).transpose() / 3.0;
    const double r = (c - kNipple).norm(), azimuth = std::atan2(c.z(), c.x()) * 180.0 / M_PI;
    const bool band = r > 10.0 && r < 14.0 && std::abs(azimuth) > 15.0;
    const bool slit = r >= 10.0 && r < 45.0 && std::abs(azimuth) > 15.0 && std::abs(azimuth) < 25.0;
    if (!(c.y() < 0 && (band || slit))) kept.push_back(sphere.F.row(f));
  }
  holed.F.resize(static_cast<Index>(kept.size()), 3);
  for (size_t k = 0; k < kept.size(); ++k) holed.F.row(static_cast<Index>(k)) = kept[k];
  return holed;
}

TEST(SkinAround, AHoleNearTheNippleDoesNotCutTheSkinOffTheBreast) {
  const TriangleMesh holed = sphere_with_hole_around_nipple();
  const Points N = mesh::vertex_normals(holed);
  const SkinPatch skin = skin_around(holed, N, skin_vertices(holed), kNipple, 40.0);
  const auto tip = breast_tip_on_scan(skin.V, skin.V, skin.N, kNipple);
  ASSERT_TRUE(tip);
  EXPECT_LT((*tip - kNipple).norm(), 1.0) << tip->transpose();
}

TEST(SkinAround, APointCloudIsSkinEverywhere) {
  TriangleMesh cloud;
  cloud.V = test::breast_with_fragment().V;
  const Points N = mesh::vertex_normals(test::breast_with_fragment());
  const SkinPatch skin = skin_around(cloud, N, skin_vertices(cloud), kNipple, 40.0);
  Index near = 0;
  for (Index i = 0; i < cloud.V.rows(); ++i) near += (cloud.V.row(i).transpose() - kNipple).norm() < 40.0;
  EXPECT_EQ(skin.V.rows(), near);  // the fragment's vertices too: a cloud has no pieces
  EXPECT_EQ(skin_around(cloud, N, skin_vertices(cloud), Vec3(0, -500, 0), 40.0).V.rows(), 0);
}

// Through the scan's index (ClosestPointIndex::vertices_within): the pass over every vertex's patch
// bit for bit — the same vertices in the same order, with their normals — on a breast with a
// fragment, a holed one, and with vertices no triangle uses (never skin), around centres on and
// off the surface, with vertices exactly at the radius (not kept: the test is strict) and a few
// ulps inside it.
TEST(SkinAround, ThroughTheIndexIsThePassOverEveryVertex) {
  TriangleMesh unused = test::breast_with_fragment();
  unused.V.conservativeResize(unused.V.rows() + 2, 3);
  unused.V.row(unused.V.rows() - 2) = kNipple.transpose();  // on the nipple, but on no triangle
  unused.V.row(unused.V.rows() - 1) << 0, -50, 0;
  for (const TriangleMesh& scan : {test::breast_with_fragment(), sphere_with_hole_around_nipple(), unused}) {
    const spatial::ClosestPointIndex index(scan);
    const Points N = mesh::vertex_normals(scan);
    const std::vector<char> skin = skin_vertices(scan);
    const Vec3 on_surface = scan.V.row(17).transpose();
    for (const Vec3& centre : {kNipple, Vec3(0, -88, 0), Vec3(10, -70, 5), on_surface, Vec3(0, -500, 0)}) {
      // Radii: the distance of a vertex from the centre exactly (that vertex is left out), a few
      // ulps more (kept), and round ones.
      const double exact = (scan.V.row(5).transpose() - centre).norm();
      for (const double radius : {40.0, 12.5, exact, std::nextafter(exact, 1e9), exact * (1 + 4e-16), 0.0}) {
        const SkinPatch by_pass = skin_around(scan, N, skin, centre, radius);
        const SkinPatch by_index = skin_around(index, N, skin, centre, radius);
        ASSERT_EQ(by_index.V.rows(), by_pass.V.rows()) << "centre " << centre.transpose() << " radius " << radius;
        EXPECT_TRUE((by_index.V.array() == by_pass.V.array()).all());
        EXPECT_TRUE((by_index.N.array() == by_pass.N.array()).all());
      }
    }
    EXPECT_GT(skin_around(index, N, skin, kNipple, 40.0).V.rows(), 100);
  }
  const spatial::ClosestPointIndex index(unused);
  const Points N = mesh::vertex_normals(unused);
  EXPECT_THROW(skin_around(index, N, skin_vertices(unused), kNipple, -1.0), InvalidInput);
}

}  // namespace
}  // namespace breastfit::fit
