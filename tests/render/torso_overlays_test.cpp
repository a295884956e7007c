// The standard overlay look shared by `breastfit render` and the report: sizes scale with the
// image, landmarks are labelled red discs, placed landmarks dark discs joined to the fitted ones,
// drawings take the one drawing palette.
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

TEST(TorsoOverlays, CurvesTakeTheDrawingPaletteByKindElseByIndex) {
  Scene scene;
  Points P(3, 3);
  P << 0, 0, 0, 1, 0, 0, 1, 1, 0;
  add_curve(scene, "a", true, P, OverlaySizes(512));
  add_curve(scene, "b", false, P, OverlaySizes(512));
  ASSERT_EQ(scene.polylines.size(), 2u);
  EXPECT_EQ(scene.polylines[0].name, "a");
  EXPECT_TRUE(scene.polylines[0].closed);
  EXPECT_FALSE(scene.polylines[1].closed);
  EXPECT_EQ(scene.polylines[0].colour, to_rgb(mesh::drawing_colour("a", 0)));
  EXPECT_EQ(scene.polylines[1].colour, to_rgb(mesh::drawing_colour("b", 1)));
  EXPECT_NE(scene.polylines[0].colour, scene.polylines[1].colour);
  EXPECT_EQ(scene.polylines[1].points, P);
  EXPECT_EQ(scene.polylines[0].width_px, 2.0);
  add_curve(scene, "sternum", false, P, OverlaySizes(512));
  EXPECT_EQ(scene.polylines[2].colour, to_rgb(mesh::drawing_colour("sternum", 0)));
}

TEST(TorsoOverlays, PlacedLandmarksAreDarkDiscsJoinedToTheFittedOnesOfTheSameName) {
  Scene scene;
  const OverlaySizes sizes(512);
  const std::vector<NamedPoint> placed = {{"nipple_R", Vec3(0, 0, 0)}, {"xiphoid", Vec3(5, 0, 0)}, {"extra", Vec3(9, 9, 9)}};
  const std::vector<NamedPoint> fitted = {{"xiphoid", Vec3(6, 1, 0)}, {"nipple_R", Vec3(0, 2, 0)}};
  add_placed_landmarks(scene, placed, fitted, sizes);
  ASSERT_EQ(scene.points.size(), 3u);  // every placed landmark, joined or not
  for (const auto& p : scene.points) {
    EXPECT_EQ(p.colour, kPlacedLandmarkColour);
    EXPECT_TRUE(p.label.empty());  // the fitted landmark carries the name
    EXPECT_LT(p.radius_px, sizes.point_radius_px);
  }
  ASSERT_EQ(scene.polylines.size(), 3u);  // two joins ("extra" has no fitted twin) and the legend entry
  EXPECT_TRUE(scene.polylines[0].points.row(0).isApprox(Vec3(0, 0, 0).transpose()));
  EXPECT_TRUE(scene.polylines[0].points.row(1).isApprox(Vec3(0, 2, 0).transpose()));
  EXPECT_TRUE(scene.polylines[1].points.row(1).isApprox(Vec3(6, 1, 0).transpose()));
  for (int k = 0; k < 2; ++k) EXPECT_TRUE(scene.polylines[k].name.empty());
  EXPECT_EQ(scene.polylines[2].name, kPlacedLandmarkLegend);
  EXPECT_EQ(scene.polylines[2].points.rows(), 0);
  EXPECT_NE(kPlacedLandmarkColour, kLandmarkColour);
  // None placed: nothing, not even a legend entry.
  Scene empty;
  add_placed_landmarks(empty, {}, fitted, sizes);
  EXPECT_TRUE(empty.points.empty());
  EXPECT_TRUE(empty.polylines.empty());
}

}  // namespace
}  // namespace breastfit::render
