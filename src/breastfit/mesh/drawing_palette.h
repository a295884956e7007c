#pragma once
/// \file The one palette of the surgical drawings and landmarks, shared by every output that
/// colours them: report.html's figures and swatches, `breastfit render`, scan_painted.ply and
/// drawings.ply, and the workstation (which receives the colours from the server). By kind:
/// breast contours blue, inframammary folds green, sternum magenta; any other drawing purple,
/// teal or dark grey by its index. Red is kept for the fitted landmarks and near-black for the
/// landmarks a person placed, so no drawing is confused with a landmark.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace breastfit::mesh {

/// An 8-bit sRGB colour as {red, green, blue}.
using Rgb8 = std::array<std::uint8_t, 3>;

/// The colour of a drawing by its name's kind ("breast_contour*", "imf*", "sternum*"); other
/// names get the `index`-th of three further colours (cycled).
Rgb8 drawing_colour(std::string_view name, std::size_t index);

/// The fitted model's landmarks: a saturated red that stands out on skin and on the colour maps.
inline constexpr Rgb8 kFittedLandmarkColour = {215, 25, 32};
/// The landmarks a person placed on the scan (drawn beside the fitted ones): near-black.
inline constexpr Rgb8 kPlacedLandmarkColour = {25, 25, 25};

}  // namespace breastfit::mesh
