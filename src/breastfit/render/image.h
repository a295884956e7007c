#pragma once
/// \file An 8-bit RGB raster image with PNG output (the render layer's canvas and result).
#include <cstdint>
#include <filesystem>
#include <vector>

namespace breastfit::render {

/// An 8-bit sRGB colour.
struct Rgb {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

/// Linear blend of two colours: `a` at t = 0, `b` at t = 1 (t clamped to [0, 1]).
Rgb mix(Rgb a, Rgb b, double t);

/// `width` by `height` RGB8 pixels, row 0 at the top, x to the right; stored row-major, packed
/// (3 bytes per pixel, no padding).
class Image {
 public:
  Image() = default;
  /// \throws InvalidInput if width or height is not positive (or the image exceeds 2^28 pixels).
  Image(int width, int height, Rgb fill = {});

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return width_ == 0 || height_ == 0; }

  /// Pixel access without bounds checks; \pre 0 <= x < width, 0 <= y < height.
  Rgb at(int x, int y) const {
    const std::uint8_t* p = &data_[3 * (static_cast<size_t>(y) * width_ + x)];
    return {p[0], p[1], p[2]};
  }
  void set(int x, int y, Rgb c) {
    std::uint8_t* p = &data_[3 * (static_cast<size_t>(y) * width_ + x)];
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
  }
  /// Bounds-checked write: pixels outside the image are ignored.
  void put(int x, int y, Rgb c) {
    if (x >= 0 && y >= 0 && x < width_ && y < height_) set(x, y, c);
  }
  /// Bounds-checked blend: pixel = mix(pixel, c, alpha).
  void blend(int x, int y, Rgb c, double alpha) {
    if (x >= 0 && y >= 0 && x < width_ && y < height_) set(x, y, mix(at(x, y), c, alpha));
  }

  void fill(Rgb c);
  /// Fills the rectangle [x0, x1) × [y0, y1), clipped to the image, blending with `alpha`.
  void fill_rect(int x0, int y0, int x1, int y1, Rgb c, double alpha = 1.0);

  /// Box-filter downsampling by an integer factor (anti-aliasing of a supersampled render).
  /// \throws InvalidInput unless factor >= 1 and it divides width and height.
  Image downsampled(int factor) const;

  /// The packed RGB bytes (width * height * 3).
  const std::vector<std::uint8_t>& bytes() const { return data_; }

  /// The image encoded as PNG (encode_png_rgb8 with its default options; deterministic: same
  /// pixels give the same bytes).
  std::vector<std::uint8_t> encode_png() const;
  /// Writes a PNG file (parent directories must exist).
  /// \throws IoError if the file cannot be written; InvalidInput if the image is empty.
  void save_png(const std::filesystem::path& path) const;

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> data_;
};

/// Reads a PNG (or any format stb_image knows) as RGB8.
/// \throws IoError if the file is missing or cannot be decoded.
Image read_png(const std::filesystem::path& path);

}  // namespace breastfit::render
