#pragma once
/// \file A fast PNG encoder for 8-bit RGB images (the report's figures, `breastfit render`):
/// one row filter for every row and libdeflate at a low level, which for rendered torsos is
/// several times faster than stb_image_write's built-in deflate and ≈ 2× faster than zlib at
/// the same level, at a similar size.
#include <cstdint>
#include <vector>

namespace breastfit::render {

/// The PNG row filters (PNG specification §9.2).
enum class PngFilter : std::uint8_t { None = 0, Sub = 1, Up = 2, Average = 3, Paeth = 4 };

/// The defaults are the fastest of the filters × levels 1–2 on the report's figures
/// (bench/pipeline/report_figures_bench.cpp, BM_EncodeFrontPng; docs/REPORT.md "Cost"): "Up" (a
/// row against the one above) at level 1.
struct PngEncodeOptions {
  int level = 1;                     ///< libdeflate's compression level: 0 (store) … 12 (smallest, slowest)
  PngFilter filter = PngFilter::Up;  ///< applied to every row
};

/// `width` × `height` packed RGB8 pixels (row 0 at the top) as PNG bytes: signature, IHDR
/// (8-bit truecolour, no interlace), one IDAT, IEND. Deterministic.
/// \throws InvalidInput for non-positive sizes, a pixel buffer of the wrong size or an invalid
///         level; std::runtime_error if libdeflate fails.
std::vector<std::uint8_t> encode_png_rgb8(const std::vector<std::uint8_t>& rgb, int width, int height,
                                          const PngEncodeOptions& options = {});

}  // namespace breastfit::render
