#include "breastfit/render/image.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>

#include <stb_image.h>

#include "breastfit/core/errors.h"
#include "breastfit/render/png_encoder.h"

namespace breastfit::render {

namespace {

std::uint8_t lerp_byte(std::uint8_t a, std::uint8_t b, double t) {
  const double v = a + (static_cast<double>(b) - a) * t;
  return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
}

}  // namespace

Rgb mix(Rgb a, Rgb b, double t) {
  t = std::clamp(t, 0.0, 1.0);
  return {lerp_byte(a.r, b.r, t), lerp_byte(a.g, b.g, t), lerp_byte(a.b, b.b, t)};
}

Image::Image(int width, int height, Rgb fill_colour) {
  if (width <= 0 || height <= 0)
    throw InvalidInput("Image: width and height must be positive, got " + std::to_string(width) +
                       "x" + std::to_string(height));
  if (static_cast<long long>(width) * height > (1LL << 28))
    throw InvalidInput("Image: " + std::to_string(width) + "x" + std::to_string(height) +
                       " exceeds the 2^28 pixel limit");
  width_ = width;
  height_ = height;
  data_.resize(static_cast<size_t>(width) * height * 3);
  fill(fill_colour);
}

void Image::fill(Rgb c) {
  if (data_.empty()) return;
  if (c.r == c.g && c.g == c.b) {  // grey (the white background): one byte value
    std::memset(data_.data(), c.r, data_.size());
    return;
  }
  const size_t row = 3 * static_cast<size_t>(width_);
  for (size_t i = 0; i < row; i += 3) {
    data_[i] = c.r;
    data_[i + 1] = c.g;
    data_[i + 2] = c.b;
  }
  for (size_t at = row; at < data_.size(); at += row) std::memcpy(&data_[at], data_.data(), row);
}

void Image::fill_rect(int x0, int y0, int x1, int y1, Rgb c, double alpha) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, width_);
  y1 = std::min(y1, height_);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) set(x, y, alpha >= 1.0 ? c : mix(at(x, y), c, alpha));
}

Image Image::downsampled(int factor) const {
  if (factor < 1 || width_ % factor != 0 || height_ % factor != 0)
    throw InvalidInput("Image::downsampled: factor " + std::to_string(factor) +
                       " must be >= 1 and divide " + std::to_string(width_) + "x" +
                       std::to_string(height_));
  if (factor == 1) return *this;
  Image out(width_ / factor, height_ / factor);
  if (factor == 2) {  // the usual supersampling: two rows at a time, bytes added in place
    const size_t in_row = 3 * static_cast<size_t>(width_), out_row = 3 * static_cast<size_t>(out.width_);
    for (int y = 0; y < out.height_; ++y) {
      const std::uint8_t* a = &data_[2 * static_cast<size_t>(y) * in_row];
      const std::uint8_t* b = a + in_row;
      std::uint8_t* o = &out.data_[static_cast<size_t>(y) * out_row];
      for (size_t x = 0; x < out_row; x += 3, a += 6, b += 6)
        for (int ch = 0; ch < 3; ++ch) o[x + ch] = static_cast<std::uint8_t>((a[ch] + a[ch + 3] + b[ch] + b[ch + 3] + 2) / 4);
    }
    return out;
  }
  const int n = factor * factor;
  for (int y = 0; y < out.height_; ++y)
    for (int x = 0; x < out.width_; ++x) {
      int sum[3] = {0, 0, 0};
      for (int dy = 0; dy < factor; ++dy) {
        const std::uint8_t* p = &data_[3 * (static_cast<size_t>(y * factor + dy) * width_ + x * factor)];
        for (int dx = 0; dx < factor; ++dx, p += 3) {
          sum[0] += p[0];
          sum[1] += p[1];
          sum[2] += p[2];
        }
      }
      out.set(x, y,
              {static_cast<std::uint8_t>((sum[0] + n / 2) / n), static_cast<std::uint8_t>((sum[1] + n / 2) / n),
               static_cast<std::uint8_t>((sum[2] + n / 2) / n)});
    }
  return out;
}

std::vector<std::uint8_t> Image::encode_png() const {
  if (empty()) throw InvalidInput("Image::encode_png: the image is empty");
  return encode_png_rgb8(data_, width_, height_);
}

void Image::save_png(const std::filesystem::path& path) const {
  const std::vector<std::uint8_t> png = encode_png();
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw IoError(path.string(), "cannot open for writing");
  f.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  f.close();
  if (!f) throw IoError(path.string(), "write failed");
}

Image read_png(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw IoError(path.string(), "cannot open for reading");
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (bytes.empty()) throw IoError(path.string(), "empty file");
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels =
      stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &channels, 3);
  if (!pixels) throw IoError(path.string(), std::string("cannot decode image: ") + stbi_failure_reason());
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const unsigned char* p = pixels + 3 * (static_cast<size_t>(y) * w + x);
      img.set(x, y, {p[0], p[1], p[2]});
    }
  stbi_image_free(pixels);
  return img;
}

}  // namespace breastfit::render
