#include "breastfit/render/colorbar.h"

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"

namespace breastfit::render {
namespace {

TEST(Colorbar, NiceTicks) {
  EXPECT_EQ(colorbar_ticks(0, 10, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(colorbar_ticks(0, 1, 3), (std::vector<double>{0, 0.5, 1}));
  const auto t = colorbar_ticks(-3.3, 7.9, 5);
  ASSERT_GE(t.size(), 3u);
  EXPECT_GE(t.front(), -3.3);
  EXPECT_LE(t.back(), 7.9);
  EXPECT_EQ(colorbar_ticks(0.31, 0.32, 2).size() >= 2, true);
  EXPECT_THROW(colorbar_ticks(1, 1), InvalidInput);
}

TEST(Colorbar, TickFormatting) {
  EXPECT_EQ(format_tick(5, 1), "5");
  EXPECT_EQ(format_tick(2.5, 2.5), "2.5");
  EXPECT_EQ(format_tick(0.25, 0.05), "0.25");
  EXPECT_EQ(format_tick(-0.0, 1), "0");
  EXPECT_EQ(format_tick(10, 5), "10");
}

TEST(Colorbar, DrawsTheGradientWithHiOnTop) {
  Image img(200, 200, {255, 255, 255});
  ColorbarSpec spec;
  spec.map = Colormap::Viridis;
  spec.lo = 0;
  spec.hi = 20;
  spec.units = "mm";
  draw_colorbar(img, 20, 10, 20, 150, spec, 1);
  // Title line (8 px + 4 px gap), then the bar from y = 22 to 171.
  EXPECT_EQ(img.at(30, 22), colormap_unit(Colormap::Viridis, 1.0));
  EXPECT_EQ(img.at(30, 171), colormap_unit(Colormap::Viridis, 0.0));
  // Tick labels drawn to the right of the bar (dark pixels).
  int dark = 0;
  for (int y = 15; y < 180; ++y)
    for (int x = 45; x < 80; ++x) dark += img.at(x, y).r < 100 ? 1 : 0;
  EXPECT_GT(dark, 30);
  const ColorbarLayout layout = colorbar_layout(spec, 20, 150, 1);
  EXPECT_GT(layout.width, 20);
  EXPECT_GT(layout.height, 150);
  EXPECT_THROW(draw_colorbar(img, 0, 0, 0, 10, spec), InvalidInput);
}

}  // namespace
}  // namespace breastfit::render
