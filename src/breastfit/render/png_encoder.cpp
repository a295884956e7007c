#include "breastfit/render/png_encoder.h"

#include <cstdlib>
#include <stdexcept>
#include <string>

#include <zlib.h>

#include "breastfit/core/errors.h"

namespace breastfit::render {
namespace {

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 24));
  out.push_back(static_cast<std::uint8_t>(v >> 16));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v));
}

/// Appends a chunk: length, type, data, CRC-32 of type and data.
void put_chunk(std::vector<std::uint8_t>& out, const char (&type)[5], const std::uint8_t* data, size_t n) {
  put_u32(out, static_cast<std::uint32_t>(n));
  const size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  if (n > 0) out.insert(out.end(), data, data + n);
  const uLong crc = crc32(0L, out.data() + start, static_cast<uInt>(4 + n));
  put_u32(out, static_cast<std::uint32_t>(crc));
}

int paeth(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return a;
  return pb <= pc ? b : c;
}

/// One filtered row: the filter byte, then the row's bytes filtered against the row above
/// (`prev`, nullptr for the first row: zeros).
void filter_row(PngFilter f, const std::uint8_t* row, const std::uint8_t* prev, size_t n, std::uint8_t* out) {
  constexpr size_t bpp = 3;
  out[0] = static_cast<std::uint8_t>(f);
  std::uint8_t* o = out + 1;
  for (size_t i = 0; i < n; ++i) {
    const int a = i >= bpp ? row[i - bpp] : 0;
    const int b = prev ? prev[i] : 0;
    const int c = (prev && i >= bpp) ? prev[i - bpp] : 0;
    int pred = 0;
    switch (f) {
      case PngFilter::None: pred = 0; break;
      case PngFilter::Sub: pred = a; break;
      case PngFilter::Up: pred = b; break;
      case PngFilter::Average: pred = (a + b) / 2; break;
      case PngFilter::Paeth: pred = paeth(a, b, c); break;
    }
    o[i] = static_cast<std::uint8_t>(row[i] - pred);
  }
}

}  // namespace

std::vector<std::uint8_t> encode_png_rgb8(const std::vector<std::uint8_t>& rgb, int width, int height,
                                          const PngEncodeOptions& options) {
  if (width <= 0 || height <= 0)
    throw InvalidInput("encode_png_rgb8: the size must be positive, got " + std::to_string(width) + "x" +
                       std::to_string(height));
  const size_t stride = 3 * static_cast<size_t>(width);
  if (rgb.size() != stride * static_cast<size_t>(height))
    throw InvalidInput("encode_png_rgb8: " + std::to_string(rgb.size()) + " bytes for a " + std::to_string(width) +
                       "x" + std::to_string(height) + " RGB image");
  if (options.zlib_level < 0 || options.zlib_level > 9)
    throw InvalidInput("encode_png_rgb8: zlib_level must be in [0, 9], got " + std::to_string(options.zlib_level));

  std::vector<std::uint8_t> filtered((stride + 1) * static_cast<size_t>(height));
  for (int y = 0; y < height; ++y)
    filter_row(options.filter, &rgb[stride * y], y > 0 ? &rgb[stride * (y - 1)] : nullptr, stride,
               &filtered[(stride + 1) * y]);

  uLongf zlen = compressBound(static_cast<uLong>(filtered.size()));
  std::vector<std::uint8_t> z(zlen);
  if (compress2(z.data(), &zlen, filtered.data(), static_cast<uLong>(filtered.size()), options.zlib_level) != Z_OK)
    throw std::runtime_error("encode_png_rgb8: zlib compress2 failed");

  std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  out.reserve(out.size() + zlen + 64);
  std::vector<std::uint8_t> ihdr;
  put_u32(ihdr, static_cast<std::uint32_t>(width));
  put_u32(ihdr, static_cast<std::uint32_t>(height));
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8 bits, truecolour, deflate, adaptive filters, no interlace
  put_chunk(out, "IHDR", ihdr.data(), ihdr.size());
  put_chunk(out, "IDAT", z.data(), zlen);
  put_chunk(out, "IEND", nullptr, 0);
  return out;
}

}  // namespace breastfit::render
