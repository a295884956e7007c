#pragma once
/// \file A built-in 5×7 bitmap font (printable ASCII, with a descender row) and text drawing, so
/// images can carry titles, landmark names and colour-bar ticks without any font files.
#include <string_view>

#include "breastfit/render/image.h"

namespace breastfit::render {

inline constexpr int kGlyphWidth = 5;    ///< glyph cell width, font pixels
inline constexpr int kGlyphHeight = 8;   ///< 7 rows above the baseline + 1 descender row
inline constexpr int kGlyphAdvance = 6;  ///< horizontal advance per character, font pixels
inline constexpr int kLineHeight = 10;   ///< vertical advance per line, font pixels

/// Pixel size of a (possibly multi-line, '\n'-separated) text at an integer scale.
struct TextSize {
  int width = 0;
  int height = 0;
};
TextSize text_size(std::string_view text, int scale = 1);

/// True when font pixel (col, row) of character `c` is set; characters outside printable ASCII
/// draw as '?'. \pre 0 <= col < kGlyphWidth, 0 <= row < kGlyphHeight.
bool glyph_pixel(char c, int col, int row);

/// Draws text with its top-left corner at (x, y); each font pixel becomes a scale×scale block.
/// Pixels outside the image are clipped. \throws InvalidInput if scale < 1.
void draw_text(Image& image, int x, int y, std::string_view text, Rgb colour, int scale = 1);

/// draw_text on a padded box blended over the image with `box_alpha` (a readable label).
void draw_label(Image& image, int x, int y, std::string_view text, Rgb colour, Rgb box_colour,
                double box_alpha = 0.75, int scale = 1, int padding = 2);

}  // namespace breastfit::render
