#include "breastfit/render/png_encoder.h"

#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>

#include <libdeflate.h>
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
  if (options.level < 0 || options.level > 12)
    throw InvalidInput("encode_png_rgb8: level must be in [0, 12], got " + std::to_string(options.level));

  std::vector<std::uint8_t> filtered((stride + 1) * static_cast<size_t>(height));
  for (int y = 0; y < height; ++y)
    filter_row(options.filter, &rgb[stride * y], y > 0 ? &rgb[stride * (y - 1)] : nullptr, stride,
               &filtered[(stride + 1) * y]);

  // The IDAT data is a zlib stream; libdeflate writes one from the whole buffer at once.
  const std::unique_ptr<libdeflate_compressor, void (*)(libdeflate_compressor*)> compressor(
      libdeflate_alloc_compressor(options.level), libdeflate_free_compressor);
  if (!compressor) throw std::runtime_error("encode_png_rgb8: libdeflate could not allocate a compressor");
  std::vector<std::uint8_t> z(libdeflate_zlib_compress_bound(compressor.get(), filtered.size()));
  const size_t zlen = libdeflate_zlib_compress(compressor.get(), filtered.data(), filtered.size(), z.data(), z.size());
  if (zlen == 0) throw std::runtime_error("encode_png_rgb8: libdeflate could not compress the image");

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
