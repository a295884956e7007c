#pragma once
/// \file Scalar → colour maps for per-vertex fields (e.g. distances in mm).
#include <string>
#include <string_view>

#include "breastfit/render/image.h"

namespace breastfit::render {

enum class Colormap {
  Viridis,       ///< perceptually uniform, dark blue-violet (lo) → yellow (hi); for magnitudes
  BlueWhiteRed,  ///< diverging, blue (lo) → white (middle) → red (hi); for signed values
  Grey,          ///< black (lo) → white (hi)
};

/// Colour of `t` in [0, 1] (clamped; NaN maps to mid grey 128,128,128).
Rgb colormap_unit(Colormap map, double t);

/// Colour of `value` with `lo` ↦ start and `hi` ↦ end of the map; values outside are clamped.
/// \throws InvalidInput unless lo < hi (both finite).
Rgb colormap(Colormap map, double value, double lo, double hi);

/// "viridis", "blue-white-red", "grey".
std::string_view colormap_name(Colormap map);
/// Inverse of colormap_name (also accepts "bwr", "gray").
/// \throws InvalidInput for unknown names, listing the known ones.
Colormap colormap_from_name(std::string_view name);

}  // namespace breastfit::render
