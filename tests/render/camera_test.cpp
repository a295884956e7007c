#include "breastfit/render/camera.h"

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"

namespace breastfit::render {
namespace {

Camera ortho_front(double view_height) {
  Camera c;
  c.eye = Vec3(0, -10, 0);
  c.target = Vec3::Zero();
  c.up = Vec3(0, 0, 1);
  c.view_height = view_height;
  return c;
}

TEST(Camera, OrthographicProjection) {
  const Camera c = ortho_front(4.0);
  const Projected centre = c.project(Vec3::Zero(), 200, 100);
  EXPECT_DOUBLE_EQ(centre.x, 100.0);
  EXPECT_DOUBLE_EQ(centre.y, 50.0);
  EXPECT_DOUBLE_EQ(centre.depth, 10.0);
  // up (+z) by half the view height → top edge; right = forward × up = +x.
  EXPECT_NEAR(c.project(Vec3(0, 0, 2), 200, 100).y, 0.0, 1e-12);
  EXPECT_NEAR(c.project(Vec3(0, 0, -2), 200, 100).y, 100.0, 1e-12);
  EXPECT_NEAR(c.project(Vec3(4, 0, 0), 200, 100).x, 200.0, 1e-12);  // aspect 2: half width = 4
  EXPECT_NEAR(c.project(Vec3(0, 3, 0), 200, 100).depth, 13.0, 1e-12);
  EXPECT_TRUE(c.right().isApprox(Vec3(1, 0, 0)));
  EXPECT_DOUBLE_EQ(c.world_per_pixel(123.0, 100), 0.04);
}

TEST(Camera, PerspectiveShrinksWithDistance) {
  Camera c = ortho_front(1.0);
  c.projection = Projection::Perspective;
  c.fov_y_deg = 40;
  const double near_x = c.project(Vec3(1, -5, 0), 100, 100).x;
  const double far_x = c.project(Vec3(1, 5, 0), 100, 100).x;
  EXPECT_GT(near_x, far_x);
  EXPECT_GT(far_x, 50.0);
  EXPECT_GT(c.world_per_pixel(20.0, 100), c.world_per_pixel(10.0, 100));
}

TEST(Camera, ValidateRejectsDegenerateCameras) {
  Camera c = ortho_front(1.0);
  EXPECT_NO_THROW(c.validate());
  c.up = Vec3(0, 1, 0);  // parallel to the view
  EXPECT_THROW(c.validate(), InvalidInput);
  c = ortho_front(1.0);
  c.target = c.eye;
  EXPECT_THROW(c.validate(), InvalidInput);
  c = ortho_front(-1.0);
  EXPECT_THROW(c.validate(), InvalidInput);
}

TEST(Camera, FramePointsKeepsEverythingInsideWithMargin) {
  Points P(4, 3);
  P << -100, 0, -50, 100, 20, 50, 30, -40, 10, -20, 10, 0;
  for (Projection proj : {Projection::Orthographic, Projection::Perspective}) {
    const Camera c = frame_points(P, Vec3(0, 1, 0), Vec3(0, 0, 1), 1.5, 0.1, proj);
    double xmin = 1e9, xmax = -1e9, ymin = 1e9, ymax = -1e9;
    for (int i = 0; i < 4; ++i) {
      const Projected q = c.project(P.row(i).transpose(), 300, 200);
      EXPECT_GT(q.depth, 0);
      xmin = std::min(xmin, q.x);
      xmax = std::max(xmax, q.x);
      ymin = std::min(ymin, q.y);
      ymax = std::max(ymax, q.y);
    }
    EXPECT_GE(xmin, 30.0 - 1e-6);
    EXPECT_LE(xmax, 270.0 + 1e-6);
    EXPECT_GE(ymin, 20.0 - 1e-6);
    EXPECT_LE(ymax, 180.0 + 1e-6);
    // Tight along the binding direction (width: 200 wide vs 100 tall at aspect 1.5).
    EXPECT_NEAR(xmax - xmin, 240.0, proj == Projection::Orthographic ? 1e-6 : 40.0);
  }
  EXPECT_THROW(frame_points(Points(0, 3), Vec3(0, 1, 0), Vec3(0, 0, 1), 1.0), InvalidInput);
  EXPECT_THROW(frame_points(P, Vec3(0, 0, 1), Vec3(0, 0, 1), 1.0), InvalidInput);
}

TEST(Camera, FrameBoxCentresTheBox) {
  const Eigen::AlignedBox3d box(Vec3(-1, -1, -1), Vec3(3, 1, 1));
  const Camera c = frame_box(box, Vec3(0, 1, 0), Vec3(0, 0, 1), 1.0, 0.0);
  const Projected q = c.project(box.center(), 100, 100);
  EXPECT_NEAR(q.x, 50.0, 1e-9);
  EXPECT_NEAR(q.y, 50.0, 1e-9);
  EXPECT_NEAR(c.view_height, 4.0, 1e-9);
}

}  // namespace
}  // namespace breastfit::render
