#include "breastfit/render/colormap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "breastfit/core/errors.h"

namespace breastfit::render {
namespace {

double luminance(Rgb c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

TEST(Colormap, ViridisEndpoints) {
  EXPECT_EQ(colormap_unit(Colormap::Viridis, 0.0), (Rgb{68, 1, 84}));
  EXPECT_EQ(colormap_unit(Colormap::Viridis, 1.0), (Rgb{253, 231, 37}));
  EXPECT_EQ(colormap(Colormap::Viridis, 2.0, 2.0, 12.0), (Rgb{68, 1, 84}));
  EXPECT_EQ(colormap(Colormap::Viridis, 12.0, 2.0, 12.0), (Rgb{253, 231, 37}));
}

TEST(Colormap, ClampsOutsideTheRange) {
  EXPECT_EQ(colormap(Colormap::Viridis, -100.0, 0.0, 1.0), colormap_unit(Colormap::Viridis, 0.0));
  EXPECT_EQ(colormap(Colormap::Viridis, 100.0, 0.0, 1.0), colormap_unit(Colormap::Viridis, 1.0));
}

TEST(Colormap, ViridisLuminanceIncreases) {
  double prev = -1;
  for (int i = 0; i <= 32; ++i) {
    const double l = luminance(colormap_unit(Colormap::Viridis, i / 32.0));
    EXPECT_GT(l, prev) << "at step " << i;
    prev = l;
  }
}

TEST(Colormap, DivergingIsBlueWhiteRed) {
  const Rgb lo = colormap(Colormap::BlueWhiteRed, -5.0, -5.0, 5.0);
  const Rgb mid = colormap(Colormap::BlueWhiteRed, 0.0, -5.0, 5.0);
  const Rgb hi = colormap(Colormap::BlueWhiteRed, 5.0, -5.0, 5.0);
  EXPECT_GT(lo.b, lo.r + 80);
  EXPECT_GT(hi.r, hi.b + 80);
  EXPECT_EQ(mid, (Rgb{247, 247, 247}));
  EXPECT_EQ(colormap_unit(Colormap::Grey, 0.0), (Rgb{0, 0, 0}));
  EXPECT_EQ(colormap_unit(Colormap::Grey, 1.0), (Rgb{255, 255, 255}));
}

TEST(Colormap, NanIsGreyAndBadRangeThrows) {
  EXPECT_EQ(colormap_unit(Colormap::Viridis, std::numeric_limits<double>::quiet_NaN()), (Rgb{128, 128, 128}));
  EXPECT_THROW(colormap(Colormap::Viridis, 1.0, 2.0, 2.0), InvalidInput);
  EXPECT_THROW(colormap(Colormap::Viridis, 1.0, 3.0, 2.0), InvalidInput);
  EXPECT_THROW(colormap(Colormap::Viridis, 1.0, 0.0, std::numeric_limits<double>::infinity()), InvalidInput);
}

TEST(Colormap, NamesRoundTrip) {
  for (Colormap m : {Colormap::Viridis, Colormap::BlueWhiteRed, Colormap::Grey})
    EXPECT_EQ(colormap_from_name(colormap_name(m)), m);
  EXPECT_EQ(colormap_from_name("bwr"), Colormap::BlueWhiteRed);
  EXPECT_THROW(colormap_from_name("jet"), InvalidInput);
}

}  // namespace
}  // namespace breastfit::render
