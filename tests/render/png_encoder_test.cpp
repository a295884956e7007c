// The PNG encoder: every filter and level decodes (stb_image) to the same pixels; the file's
// structure (signature, IHDR, chunk CRCs); invalid input is refused; deterministic.
#include "breastfit/render/png_encoder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <zlib.h>

#include "breastfit/core/errors.h"
#include "breastfit/render/image.h"
#include "support/test_paths.h"

namespace breastfit::render {
namespace {

/// A test picture with smooth gradients, hard edges and noise (every filter's case).
Image picture(int w, int h) {
  Image img(w, h);
  std::uint32_t seed = 12345;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      seed = seed * 1664525u + 1013904223u;
      const std::uint8_t noise = static_cast<std::uint8_t>(seed >> 27);
      img.set(x, y, {static_cast<std::uint8_t>(x * 255 / w), static_cast<std::uint8_t>((x / 7 + y / 5) % 2 ? 200 : 30),
                     static_cast<std::uint8_t>(y * 3 + noise)});
    }
  return img;
}

Image decode(const std::vector<std::uint8_t>& png) {
  const std::filesystem::path f = test::temp_dir() / "t.png";
  std::ofstream(f, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  return read_png(f);
}

std::uint32_t u32(const std::vector<std::uint8_t>& b, size_t at) {
  return (std::uint32_t(b[at]) << 24) | (std::uint32_t(b[at + 1]) << 16) | (std::uint32_t(b[at + 2]) << 8) | b[at + 3];
}

TEST(PngEncoder, EveryFilterAndLevelDecodesToTheSamePixels) {
  const Image img = picture(37, 23);
  for (PngFilter f : {PngFilter::None, PngFilter::Sub, PngFilter::Up, PngFilter::Average, PngFilter::Paeth})
    for (int level : {0, 1, 6, 9, 12}) {
      const Image back = decode(encode_png_rgb8(img.bytes(), img.width(), img.height(), {level, f}));
      ASSERT_EQ(back.width(), 37);
      ASSERT_EQ(back.height(), 23);
      EXPECT_EQ(back.bytes(), img.bytes()) << "filter " << int(f) << " level " << level;
    }
  EXPECT_EQ(decode(img.encode_png()).bytes(), img.bytes());
}

TEST(PngEncoder, ChunksAreWellFormed) {
  const Image img = picture(20, 10);
  const std::vector<std::uint8_t> png = encode_png_rgb8(img.bytes(), 20, 10);
  ASSERT_GT(png.size(), 8u + 25u + 12u + 12u);
  EXPECT_EQ(std::vector<std::uint8_t>(png.begin(), png.begin() + 8),
            (std::vector<std::uint8_t>{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'}));
  size_t at = 8;
  std::vector<std::string> types;
  while (at < png.size()) {
    const std::uint32_t n = u32(png, at);
    const std::string type(png.begin() + at + 4, png.begin() + at + 8);
    types.push_back(type);
    const uLong crc = crc32(0L, png.data() + at + 4, 4 + n);
    EXPECT_EQ(u32(png, at + 8 + n), static_cast<std::uint32_t>(crc)) << type;
    if (type == "IHDR") {
      EXPECT_EQ(u32(png, at + 8), 20u);
      EXPECT_EQ(u32(png, at + 12), 10u);
      EXPECT_EQ(png[at + 16], 8);  // bit depth
      EXPECT_EQ(png[at + 17], 2);  // truecolour
    }
    at += 12 + n;
  }
  EXPECT_EQ(at, png.size());
  EXPECT_EQ(types, (std::vector<std::string>{"IHDR", "IDAT", "IEND"}));
}

TEST(PngEncoder, DeterministicAndSmallerAtHigherLevels) {
  const Image img = picture(200, 120);
  EXPECT_EQ(encode_png_rgb8(img.bytes(), 200, 120), encode_png_rgb8(img.bytes(), 200, 120));
  EXPECT_LE(encode_png_rgb8(img.bytes(), 200, 120, {12, PngFilter::Sub}).size(),
            encode_png_rgb8(img.bytes(), 200, 120, {0, PngFilter::Sub}).size());
}

TEST(PngEncoder, RefusesInvalidInput) {
  const std::vector<std::uint8_t> px(3 * 4 * 4, 0);
  EXPECT_THROW(encode_png_rgb8(px, 0, 4), InvalidInput);
  EXPECT_THROW(encode_png_rgb8(px, 4, 5), InvalidInput);
  EXPECT_THROW(encode_png_rgb8(px, 4, 4, {13, PngFilter::Sub}), InvalidInput);
  EXPECT_THROW(encode_png_rgb8(px, 4, 4, {-1, PngFilter::Sub}), InvalidInput);
  EXPECT_NO_THROW(encode_png_rgb8(px, 4, 4));
}

}  // namespace
}  // namespace breastfit::render
