#pragma once
/// \file The rasterizer's adaptive surface path (RasterOptions::adaptive_supersample; private to
/// the render layer): the surface found at one sample per output pixel, supersampled only at the
/// pixels next to an edge (a change of coverage or facing, a jump of depth).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "breastfit/render/detail/raster_setup.h"
#include "breastfit/render/detail/surface_draw.h"

namespace breastfit::render::detail {

/// Draws `draw` into the empty buffers of `target` (the first surface of an orthographic view,
/// every corner in the fixed-point range). Pass 1 at one sample per output pixel (its centre);
/// the pixels next to a change of coverage, of facing or a jump of depth (silhouettes, folds,
/// the scan's holes and borders) are marked (mark_edges) and pass 1 runs again over their
/// ss × ss samples only; pass 2 lights an unmarked pixel once, at its centre, and shades a
/// marked one sample by sample (once when a single triangle covers all of it). The buffers are
/// filled as draw_supersampled fills them (an unmarked pixel's colour and depth in all its
/// samples), so the overlays and the resolved image see no difference.
void draw_edge_refined(const SurfaceDraw& draw, SurfaceTarget& target);

/// Pass 1 at one sample per output pixel (its centre): each pixel's nearest triangle.
struct PixelCentres {
  int width = 0, height = 0;         ///< output pixels
  std::vector<float> depth;          ///< the winner's depth, kEmpty where none
  std::vector<std::int32_t> winner;  ///< the nearest triangle, −1 where none
  Box won;                           ///< around the pixels won
};

/// The pixels to refine (1, else 0, per pixel): both pixels of each 8-neighbour pair, within one
/// pixel of the pixels won, that differ in coverage, in facing (`front`, per triangle) or in depth
/// by more than `edge_depth` (world units).
std::vector<std::uint8_t> mark_edges(const PixelCentres& centres, const std::vector<std::uint8_t>& front,
                                     double edge_depth);

/// The marked pixels of a width × height grid numbered in raster order (the slots of their
/// samples) and counted in a summed-area table (how many in a box: four lookups).
class MarkedPixels {
 public:
  /// \param mark one byte per pixel, row-major, non-zero where marked.
  MarkedPixels(const std::vector<std::uint8_t>& mark, int width, int height);

  std::int32_t count() const { return count_; }
  /// Pixel p's (y · width + x) number among the marked pixels, −1 when it is not marked.
  std::int32_t slot(size_t p) const { return slot_[p]; }
  /// True when a pixel of [x0, x1] × [y0, y1] (inclusive) is marked.
  bool any_in(int x0, int y0, int x1, int y1) const {
    const size_t r0 = static_cast<size_t>(y0) * (width_ + 1), r1 = static_cast<size_t>(y1 + 1) * (width_ + 1);
    return sat_[r1 + x1 + 1] - sat_[r1 + x0] - sat_[r0 + x1 + 1] + sat_[r0 + x0] > 0;
  }

 private:
  int width_;
  std::int32_t count_ = 0;
  std::vector<std::int32_t> slot_;
  std::vector<std::int32_t> sat_;  // (width + 1) × (height + 1): marks above and left of each corner
};

}  // namespace breastfit::render::detail
