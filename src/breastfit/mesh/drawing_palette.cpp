#include "breastfit/mesh/drawing_palette.h"

namespace breastfit::mesh {

Rgb8 drawing_colour(std::string_view name, std::size_t index) {
  if (name.rfind("breast_contour", 0) == 0) return {20, 90, 200};  // blue
  if (name.rfind("imf", 0) == 0) return {0, 140, 60};              // green
  if (name.rfind("sternum", 0) == 0) return {200, 30, 130};        // magenta
  static constexpr std::array<Rgb8, 3> kOthers = {{
      {110, 50, 200},  // purple
      {0, 145, 160},   // teal
      {60, 60, 60},    // dark grey
  }};
  return kOthers[index % kOthers.size()];
}

}  // namespace breastfit::mesh
