#include "breastfit/render/view.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "breastfit/core/errors.h"
#include "breastfit/render/camera.h"

namespace breastfit::render {
namespace {

TEST(View, BodyFrameDirections) {
  const ViewDirections front = view_directions(View::Front);
  EXPECT_TRUE(front.forward.isApprox(Vec3(0, 1, 0)));  // camera anterior (−y), looking +y
  EXPECT_TRUE(front.up.isApprox(Vec3(0, 0, 1)));
  // Image right = forward × up = +x = patient's LEFT: the patient's right is on the viewer's left.
  EXPECT_TRUE(front.forward.cross(front.up).isApprox(Vec3(1, 0, 0)));
  const ViewDirections side = view_directions(View::Side);
  EXPECT_TRUE(side.forward.isApprox(Vec3(1, 0, 0)));  // from the patient's right
  EXPECT_TRUE(side.forward.cross(side.up).isApprox(Vec3(0, -1, 0)));  // anterior on the right
  const ViewDirections oblique = view_directions(View::Oblique);
  EXPECT_NEAR(oblique.forward.dot(front.forward), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(oblique.forward.dot(side.forward), std::sqrt(0.5), 1e-12);
  EXPECT_TRUE(view_directions(View::Back).forward.isApprox(Vec3(0, -1, 0)));
  EXPECT_TRUE(view_directions(View::SideLeft).forward.isApprox(Vec3(-1, 0, 0)));  // camera at the patient's left
  EXPECT_TRUE(view_directions(View::ObliqueLeft).forward.isApprox(Vec3(-1, 1, 0).normalized()));
  EXPECT_TRUE(view_directions(View::SideLeft).up.isApprox(Vec3(0, 0, 1)));
  const ViewDirections top = view_directions(View::Top);
  EXPECT_TRUE(top.forward.isApprox(Vec3(0, 0, -1)));
  EXPECT_TRUE(top.up.isApprox(Vec3(0, -1, 0)));  // anterior up in the image
}

TEST(View, FrontViewPutsPatientRightOnImageLeft) {
  const ViewDirections d = view_directions(View::Front);
  Camera c;
  c.eye = -d.forward * 1000;
  c.target = Vec3::Zero();
  c.up = d.up;
  c.view_height = 500;
  EXPECT_LT(c.project(Vec3(-100, 0, 0), 512, 512).x, 256.0);  // x < 0: patient's right
  EXPECT_GT(c.project(Vec3(100, 0, 0), 512, 512).x, 256.0);
  EXPECT_LT(c.project(Vec3(0, 0, 100), 512, 512).y, 256.0);  // superior is up
}

TEST(View, FollowsTheBodyToWorldRotation) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  T.topLeftCorner<3, 3>() = 2.5 * R;  // scale is ignored
  T.block<3, 1>(0, 3) = Vec3(10, 20, 30);
  for (View v : all_views()) {
    const ViewDirections body = view_directions(v);
    const ViewDirections world = view_directions(v, T);
    EXPECT_TRUE(world.forward.isApprox(R * body.forward, 1e-9)) << view_name(v);
    EXPECT_TRUE(world.up.isApprox(R * body.up, 1e-9)) << view_name(v);
  }
  Eigen::Matrix4d singular = Eigen::Matrix4d::Identity();
  singular(2, 2) = 0;
  EXPECT_THROW(view_directions(View::Front, singular), InvalidInput);
}

TEST(View, Names) {
  for (View v : all_views()) EXPECT_EQ(view_from_name(view_name(v)), v);
  EXPECT_EQ(all_views().size(), 7u);
  EXPECT_EQ(view_from_name("side-right"), View::Side);
  EXPECT_EQ(view_from_name("oblique-right"), View::Oblique);
  EXPECT_THROW(view_from_name("left"), InvalidInput);
  const auto views = default_views();
  ASSERT_EQ(views.size(), 5u);
  EXPECT_EQ(views[0], View::Front);
  EXPECT_EQ(views[1], View::Side);
  EXPECT_EQ(views[2], View::SideLeft);
  EXPECT_EQ(views[3], View::Oblique);
  EXPECT_EQ(views[4], View::ObliqueLeft);
}

}  // namespace
}  // namespace breastfit::render
