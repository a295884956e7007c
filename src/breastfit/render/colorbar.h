#pragma once
/// \file A vertical colour bar with "nice" tick labels and a units label, drawn into an image.
#include <string>
#include <vector>

#include "breastfit/render/colormap.h"
#include "breastfit/render/image.h"

namespace breastfit::render {

struct ColorbarSpec {
  Colormap map = Colormap::Viridis;
  double lo = 0.0;             ///< value at the bottom of the bar
  double hi = 1.0;             ///< value at the top of the bar (> lo)
  std::string units = "mm";    ///< drawn above the bar (with `label`, if any)
  std::string label;           ///< quantity name, e.g. "distance"; may be empty
  int target_ticks = 5;        ///< about this many ticks (1-2-5 steps)
};

/// Tick values: multiples of a 1-2-5 step inside [lo, hi], about `target` of them (at least the
/// two ends when no multiple fits). \throws InvalidInput unless lo < hi, finite.
std::vector<double> colorbar_ticks(double lo, double hi, int target = 5);

/// A tick label with as many decimals as the tick step needs ("0", "2.5", "-0.25").
std::string format_tick(double value, double step);

/// Size in pixels of the whole colour bar (bar, ticks, labels, title) at a text scale.
struct ColorbarLayout {
  int width = 0;
  int height = 0;
};
ColorbarLayout colorbar_layout(const ColorbarSpec& spec, int bar_width, int bar_height, int text_scale);

/// Draws the bar with its top-left corner at (x, y): the units/label line on top, the gradient
/// (bar_width × bar_height, `hi` at the top) below it with a dark frame, ticks and labels on the
/// right. \throws InvalidInput unless lo < hi and the sizes are positive.
void draw_colorbar(Image& image, int x, int y, int bar_width, int bar_height, const ColorbarSpec& spec,
                   int text_scale = 1, Rgb text_colour = {30, 30, 30});

}  // namespace breastfit::render
