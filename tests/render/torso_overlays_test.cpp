// The standard overlay look shared by `breastfit render` and the report: sizes scale with the
// image, landmarks are labelled red discs, drawings take successive palette colours.
#include <gtest/gtest.h>

#include "breastfit/render/torso_overlays.h"

namespace breastfit::render {
namespace {

TEST(TorsoOverlays, SizesScaleWithTheImageAndHaveAFloor) {
  const OverlaySizes big(1024);
  EXPECT_NEAR(big.point_radius_px, 1024 / 170.0, 1e-12);
  EXPECT_NEAR(big.line_width_px, 1024 / 340.0, 1e-12);
  const OverlaySizes small(100);
  EXPECT_EQ(small.point_radius_px, 3.0);
  EXPECT_EQ(small.line_width_px, 2.0);
}

TEST(TorsoOverlays, LandmarksAreLabelledRedDiscs) {
  const ScenePoint p = landmark_point("nipple_R", Vec3(1, 2, 3), OverlaySizes(1024));
  EXPECT_EQ(p.label, "nipple_R");
  EXPECT_EQ(p.position, Vec3(1, 2, 3));
  EXPECT_EQ(p.colour, kLandmarkColour);
  EXPECT_EQ(p.radius_unit, SizeUnit::Pixels);
  EXPECT_NEAR(p.radius_px, 1024 / 170.0, 1e-12);
}

TEST(TorsoOverlays, CurvesTakeSuccessivePaletteColours) {
  Scene scene;
  Points P(3, 3);
  P << 0, 0, 0, 1, 0, 0, 1, 1, 0;
  add_curve(scene, "a", true, P, OverlaySizes(512));
  add_curve(scene, "b", false, P, OverlaySizes(512));
  ASSERT_EQ(scene.polylines.size(), 2u);
  EXPECT_EQ(scene.polylines[0].name, "a");
  EXPECT_TRUE(scene.polylines[0].closed);
  EXPECT_FALSE(scene.polylines[1].closed);
  EXPECT_EQ(scene.polylines[0].colour, palette_colour(0));
  EXPECT_EQ(scene.polylines[1].colour, palette_colour(1));
  EXPECT_NE(scene.polylines[0].colour, scene.polylines[1].colour);
  EXPECT_EQ(scene.polylines[1].points, P);
  EXPECT_EQ(scene.polylines[0].width_px, 2.0);
}

}  // namespace
}  // namespace breastfit::render
