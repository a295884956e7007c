#pragma once
/// \file The rasterizer's full surface path (private to the render layer): every sample of every
/// triangle, over whatever the buffers already hold.
#include "breastfit/render/detail/surface_draw.h"

namespace breastfit::render::detail {

/// Draws `draw` into `target` at every sample. Pass 1 finds each sample's nearest triangle (exact
/// fixed-point edges for orthographic views, perspective-correct depths otherwise); pass 2 lights
/// an output pixel whose samples all show one smooth patch once, the others sample by sample.
void draw_supersampled(const SurfaceDraw& draw, SurfaceTarget& target);

}  // namespace breastfit::render::detail
