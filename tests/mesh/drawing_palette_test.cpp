#include "breastfit/mesh/drawing_palette.h"

#include <gtest/gtest.h>

namespace breastfit::mesh {
namespace {

TEST(DrawingPalette, ColoursByKindWhateverTheIndex) {
  for (std::size_t i : {0u, 1u, 5u}) {
    EXPECT_EQ(drawing_colour("breast_contour_R", i), drawing_colour("breast_contour_L", 0));
    EXPECT_EQ(drawing_colour("imf_L", i), drawing_colour("imf_R", 3));
    EXPECT_EQ(drawing_colour("sternum", i), drawing_colour("sternum_line", 2));
  }
  EXPECT_NE(drawing_colour("breast_contour_R", 0), drawing_colour("imf_R", 0));
  EXPECT_NE(drawing_colour("imf_R", 0), drawing_colour("sternum", 0));
  EXPECT_NE(drawing_colour("sternum", 0), drawing_colour("breast_contour_R", 0));
}

TEST(DrawingPalette, OtherDrawingsCycleThreeColoursDistinctFromTheKindsAndLandmarks) {
  EXPECT_EQ(drawing_colour("incision", 0), drawing_colour("other", 3));
  EXPECT_NE(drawing_colour("incision", 0), drawing_colour("incision", 1));
  EXPECT_NE(drawing_colour("incision", 1), drawing_colour("incision", 2));
  for (std::size_t i = 0; i < 3; ++i) {
    const Rgb8 c = drawing_colour("x", i);
    for (const char* kind : {"breast_contour_R", "imf_R", "sternum"}) EXPECT_NE(c, drawing_colour(kind, 0));
    EXPECT_NE(c, kFittedLandmarkColour);
    EXPECT_NE(c, kPlacedLandmarkColour);
  }
}

}  // namespace
}  // namespace breastfit::mesh
