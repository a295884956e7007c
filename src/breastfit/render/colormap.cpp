#include "breastfit/render/colormap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "breastfit/core/errors.h"

namespace breastfit::render {

namespace {

// matplotlib's viridis (CC0, van der Walt & Smith) sampled at 33 evenly spaced points; linear
// interpolation between them stays within 3/255 of the full map.
constexpr std::array<Rgb, 33> kViridis = {{
    {68, 1, 84},    {71, 13, 96},   {72, 24, 106},  {72, 35, 116},  {71, 45, 123},  {69, 55, 129},
    {66, 64, 134},  {62, 73, 137},  {59, 82, 139},  {55, 91, 141},  {51, 99, 141},  {47, 107, 142},
    {44, 114, 142}, {41, 122, 142}, {38, 130, 142}, {35, 137, 142}, {33, 145, 140}, {31, 152, 139},
    {31, 160, 136}, {34, 167, 133}, {40, 174, 128}, {50, 182, 122}, {63, 188, 115}, {78, 195, 107},
    {94, 201, 98},  {112, 207, 87}, {132, 212, 75}, {152, 216, 62}, {173, 220, 48}, {194, 223, 35},
    {216, 226, 25}, {236, 229, 27}, {253, 231, 37},
}};

// Diverging map: saturated blue → light blue → white → light red → saturated red.
constexpr std::array<Rgb, 5> kBlueWhiteRed = {{
    {33, 82, 166}, {125, 170, 220}, {247, 247, 247}, {230, 134, 110}, {165, 20, 38},
}};

template <size_t N>
Rgb sample(const std::array<Rgb, N>& table, double t) {
  const double s = t * (N - 1);
  const size_t i = std::min(static_cast<size_t>(s), N - 2);
  return mix(table[i], table[i + 1], s - static_cast<double>(i));
}

}  // namespace

Rgb colormap_unit(Colormap map, double t) {
  if (std::isnan(t)) return {128, 128, 128};
  t = std::clamp(t, 0.0, 1.0);
  switch (map) {
    case Colormap::Viridis:
      return sample(kViridis, t);
    case Colormap::BlueWhiteRed:
      return sample(kBlueWhiteRed, t);
    case Colormap::Grey: {
      const auto v = static_cast<std::uint8_t>(std::lround(255.0 * t));
      return {v, v, v};
    }
  }
  return {128, 128, 128};
}

Rgb colormap(Colormap map, double value, double lo, double hi) {
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo < hi))
    throw InvalidInput("colormap: need finite lo < hi, got lo=" + std::to_string(lo) +
                       " hi=" + std::to_string(hi));
  return colormap_unit(map, (value - lo) / (hi - lo));
}

std::string_view colormap_name(Colormap map) {
  switch (map) {
    case Colormap::Viridis:
      return "viridis";
    case Colormap::BlueWhiteRed:
      return "blue-white-red";
    case Colormap::Grey:
      return "grey";
  }
  return "viridis";
}

Colormap colormap_from_name(std::string_view name) {
  if (name == "viridis") return Colormap::Viridis;
  if (name == "blue-white-red" || name == "bwr") return Colormap::BlueWhiteRed;
  if (name == "grey" || name == "gray") return Colormap::Grey;
  throw InvalidInput("unknown colour map '" + std::string(name) +
                     "' (known: viridis, blue-white-red, grey)");
}

}  // namespace breastfit::render
