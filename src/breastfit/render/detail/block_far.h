#pragma once
/// \file The coarse depth test of the rasterizer's back faces (private to the render layer).
#include <algorithm>
#include <cstddef>
#include <vector>

namespace breastfit::render::detail {

/// The farthest depth drawn in each block of kBlock × kBlock pixels of a w × h grid (+inf where a
/// pixel is empty), for the coarse depth test of the back faces: a triangle no nearer than that over
/// all the blocks of its box fails the depth test at every pixel.
class BlockFar {
 public:
  static constexpr int kBlock = 8;
  BlockFar(int w, int h) : w_(w), h_(h), blocks_x_((w + kBlock - 1) / kBlock), blocks_y_((h + kBlock - 1) / kBlock) {}
  /// Fills the blocks from `pixel_far(y · w + x)`, the farthest depth at pixel (x, y).
  template <class PixelFar>
  void fill(PixelFar&& pixel_far) {
    far_.assign(static_cast<size_t>(blocks_x_) * blocks_y_, 0.0f);
    for (int y = 0; y < h_; ++y) {
      float* out = &far_[static_cast<size_t>(y / kBlock) * blocks_x_];
      for (int x = 0; x < w_; ++x) out[x / kBlock] = std::max(out[x / kBlock], pixel_far(static_cast<size_t>(y) * w_ + x));
    }
  }
  /// True when `nearest` is no nearer than the farthest depth over the pixels [x0, x1] × [y0, y1].
  bool hidden(int x0, int y0, int x1, int y1, double nearest) const {
    for (int by = y0 / kBlock; by <= y1 / kBlock; ++by)
      for (int bx = x0 / kBlock; bx <= x1 / kBlock; ++bx)
        if (nearest < far_[static_cast<size_t>(by) * blocks_x_ + bx]) return false;
    return true;
  }

 private:
  int w_, h_, blocks_x_, blocks_y_;
  std::vector<float> far_;
};

}  // namespace breastfit::render::detail
