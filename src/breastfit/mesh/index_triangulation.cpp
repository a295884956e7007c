#include "breastfit/mesh/index_triangulation.h"

namespace breastfit::mesh {
namespace {

/// Appends (a, b, c) unless it repeats an index; returns 1 when appended.
int append_triangle(Index a, Index b, Index c, std::vector<Index>& tris) {
  if (a == b || b == c || a == c) return 0;
  tris.push_back(a);
  tris.push_back(b);
  tris.push_back(c);
  return 1;
}

}  // namespace

int append_fan_triangles(const Index* corners, std::size_t count, std::vector<Index>& tris) {
  int appended = 0;
  for (std::size_t i = 1; i + 1 < count; ++i)
    appended += append_triangle(corners[0], corners[i], corners[i + 1], tris);
  return appended;
}

int append_strip_triangles(const Index* strip, std::size_t count, std::vector<Index>& tris) {
  int appended = 0;
  for (std::size_t i = 0; i + 2 < count; ++i) {
    // Odd triangles swap their first two corners to keep the strip's winding.
    if (i % 2 == 0) {
      appended += append_triangle(strip[i], strip[i + 1], strip[i + 2], tris);
    } else {
      appended += append_triangle(strip[i + 1], strip[i], strip[i + 2], tris);
    }
  }
  return appended;
}

}  // namespace breastfit::mesh
