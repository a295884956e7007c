#include "breastfit/render/image.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "breastfit/core/errors.h"
#include "support/test_paths.h"

namespace breastfit::render {
namespace {

TEST(Image, RejectsNonPositiveSize) {
  EXPECT_THROW(Image(0, 5), InvalidInput);
  EXPECT_THROW(Image(5, -1), InvalidInput);
}

TEST(Image, FillSetAndReadBack) {
  Image img(4, 3, {10, 20, 30});
  EXPECT_EQ(img.width(), 4);
  EXPECT_EQ(img.height(), 3);
  EXPECT_EQ(img.bytes().size(), 4u * 3u * 3u);
  EXPECT_EQ(img.at(3, 2), (Rgb{10, 20, 30}));
  img.set(1, 2, {255, 0, 7});
  EXPECT_EQ(img.at(1, 2), (Rgb{255, 0, 7}));
  // Row-major packed layout: (x=1, y=2) is pixel 2*4+1.
  EXPECT_EQ(img.bytes()[3 * (2 * 4 + 1)], 255);
  img.put(-1, 0, {1, 1, 1});  // clipped, no crash
  img.put(4, 0, {1, 1, 1});
  EXPECT_EQ(img.at(0, 0), (Rgb{10, 20, 30}));
}

TEST(Image, FillRectClipsAndBlends) {
  Image img(4, 4, {0, 0, 0});
  img.fill_rect(-2, -2, 2, 2, {200, 100, 50}, 0.5);
  EXPECT_EQ(img.at(0, 0), (Rgb{100, 50, 25}));
  EXPECT_EQ(img.at(1, 1), (Rgb{100, 50, 25}));
  EXPECT_EQ(img.at(2, 2), (Rgb{0, 0, 0}));
}

TEST(Image, MixEndpoints) {
  EXPECT_EQ(mix({0, 0, 0}, {255, 255, 255}, 0.0), (Rgb{0, 0, 0}));
  EXPECT_EQ(mix({0, 0, 0}, {255, 255, 255}, 1.0), (Rgb{255, 255, 255}));
  EXPECT_EQ(mix({0, 0, 0}, {200, 100, 0}, 0.5), (Rgb{100, 50, 0}));
  EXPECT_EQ(mix({0, 0, 0}, {200, 100, 0}, 7.0), (Rgb{200, 100, 0}));  // clamped
}

TEST(Image, DownsampleAveragesBlocks) {
  Image img(4, 2, {0, 0, 0});
  img.set(0, 0, {255, 255, 255});
  img.set(1, 1, {255, 255, 255});
  img.set(2, 0, {100, 0, 0});
  const Image small = img.downsampled(2);
  ASSERT_EQ(small.width(), 2);
  ASSERT_EQ(small.height(), 1);
  EXPECT_EQ(small.at(0, 0), (Rgb{128, 128, 128}));  // (255 + 255) / 4, rounded
  EXPECT_EQ(small.at(1, 0), (Rgb{25, 0, 0}));
  EXPECT_THROW(img.downsampled(3), InvalidInput);
  EXPECT_THROW(img.downsampled(0), InvalidInput);
}

TEST(Image, FillAndDownsampleEveryPixel) {
  // Grey and coloured fills reach every pixel; factor 2 (its own loop) and 3 average every
  // block, rounded half up.
  for (const Rgb c : {Rgb{255, 255, 255}, Rgb{10, 20, 30}}) {
    Image img(7, 5, {1, 2, 3});
    img.fill(c);
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 7; ++x) EXPECT_EQ(img.at(x, y), c) << x << " " << y;
  }
  Image img(12, 6);
  std::uint32_t seed = 7;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 12; ++x) {
      seed = seed * 1664525u + 1013904223u;
      img.set(x, y, {static_cast<std::uint8_t>(seed >> 24), static_cast<std::uint8_t>(seed >> 16), static_cast<std::uint8_t>(seed >> 8)});
    }
  for (int f : {2, 3}) {
    const Image small = img.downsampled(f);
    ASSERT_EQ(small.width(), 12 / f);
    for (int y = 0; y < small.height(); ++y)
      for (int x = 0; x < small.width(); ++x) {
        int sum[3] = {0, 0, 0};
        for (int dy = 0; dy < f; ++dy)
          for (int dx = 0; dx < f; ++dx) {
            const Rgb p = img.at(x * f + dx, y * f + dy);
            sum[0] += p.r;
            sum[1] += p.g;
            sum[2] += p.b;
          }
        const int n = f * f;
        EXPECT_EQ(small.at(x, y), (Rgb{static_cast<std::uint8_t>((sum[0] + n / 2) / n), static_cast<std::uint8_t>((sum[1] + n / 2) / n),
                                       static_cast<std::uint8_t>((sum[2] + n / 2) / n)}))
            << f << ": " << x << " " << y;
      }
  }
}

TEST(Image, PngRoundTripAndDeterminism) {
  Image img(17, 9, {250, 250, 250});
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 17; ++x)
      if ((x + y) % 3 == 0) img.set(x, y, {static_cast<std::uint8_t>(x * 15), static_cast<std::uint8_t>(y * 28), 77});
  const auto path = test::temp_dir() / "round_trip.png";
  img.save_png(path);
  ASSERT_TRUE(std::filesystem::exists(path));
  const Image back = read_png(path);
  ASSERT_EQ(back.width(), 17);
  ASSERT_EQ(back.height(), 9);
  EXPECT_EQ(back.bytes(), img.bytes());
  // PNG signature and identical bytes on a second encode.
  const auto png = img.encode_png();
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png[1], 'P');
  EXPECT_EQ(png[2], 'N');
  EXPECT_EQ(png[3], 'G');
  EXPECT_EQ(png, img.encode_png());
}

TEST(Image, IoErrors) {
  const auto dir = test::temp_dir();
  EXPECT_THROW(read_png(dir / "missing.png"), IoError);
  EXPECT_THROW(Image(2, 2).save_png(dir / "no_such_dir" / "x.png"), IoError);
  const auto junk = dir / "junk.png";
  {
    std::FILE* f = std::fopen(junk.c_str(), "wb");
    std::fputs("not a png at all", f);
    std::fclose(f);
  }
  EXPECT_THROW(read_png(junk), IoError);
  EXPECT_THROW(Image().encode_png(), InvalidInput);
}

}  // namespace
}  // namespace breastfit::render
