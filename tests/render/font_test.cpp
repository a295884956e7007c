#include "breastfit/render/font.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "breastfit/core/errors.h"

namespace breastfit::render {
namespace {

std::string bitmap(char c) {
  std::string s;
  for (int r = 0; r < kGlyphHeight; ++r)
    for (int col = 0; col < kGlyphWidth; ++col) s += glyph_pixel(c, col, r) ? '#' : '.';
  return s;
}

TEST(Font, TextSize) {
  EXPECT_EQ(text_size("", 1).width, 0);
  const TextSize one = text_size("abc", 1);
  EXPECT_EQ(one.width, 2 * kGlyphAdvance + kGlyphWidth);
  EXPECT_EQ(one.height, kGlyphHeight);
  const TextSize two = text_size("abc", 2);
  EXPECT_EQ(two.width, 2 * one.width);
  EXPECT_EQ(two.height, 2 * one.height);
  const TextSize lines = text_size("ab\nlonger", 1);
  EXPECT_EQ(lines.width, 5 * kGlyphAdvance + kGlyphWidth);
  EXPECT_EQ(lines.height, kLineHeight + kGlyphHeight);
  EXPECT_THROW(text_size("x", 0), InvalidInput);
}

TEST(Font, EveryPrintableGlyphIsDistinctAndInked) {
  std::set<std::string> seen;
  for (int c = 33; c <= 126; ++c) {
    const std::string b = bitmap(static_cast<char>(c));
    EXPECT_NE(b.find('#'), std::string::npos) << "glyph '" << static_cast<char>(c) << "' is blank";
    EXPECT_TRUE(seen.insert(b).second) << "glyph '" << static_cast<char>(c) << "' duplicates another";
  }
  EXPECT_EQ(bitmap(' ').find('#'), std::string::npos);
  EXPECT_EQ(bitmap('\x01'), bitmap('?'));  // non-printable → '?'
}

TEST(Font, DescendersUseTheLastRowOnly) {
  for (char c : std::string("gjpqy_"))
    EXPECT_NE(bitmap(c).substr(7 * kGlyphWidth).find('#'), std::string::npos) << c;
  for (char c : std::string("ABCacex019"))
    EXPECT_EQ(bitmap(c).substr(7 * kGlyphWidth).find('#'), std::string::npos) << c;
}

TEST(Font, DrawTextInksOnlyItsBox) {
  Image img(60, 30, {255, 255, 255});
  draw_text(img, 5, 4, "Hi_2", {0, 0, 0}, 2);
  const TextSize ts = text_size("Hi_2", 2);
  int inked = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      if (img.at(x, y) == Rgb{0, 0, 0}) {
        ++inked;
        EXPECT_TRUE(x >= 5 && x < 5 + ts.width && y >= 4 && y < 4 + ts.height) << x << "," << y;
      }
    }
  // 'H' alone has 17 font pixels, each a 2×2 block.
  EXPECT_GT(inked, 4 * 17);
  // Clipping at the border does not crash.
  draw_text(img, -7, -3, "clipped", {0, 0, 0}, 3);
  draw_label(img, 55, 25, "edge", {0, 0, 0}, {200, 200, 200});
}

}  // namespace
}  // namespace breastfit::render
