#pragma once
/// \file Triangulating one polygon face of a mesh file by its corner positions (private to the
/// io layer): convex polygons keep the fan (c0, ci, ci+1) readers have always produced,
/// concave ones are ear-clipped in their best-fit plane so no triangle covers the notch.
#include <array>
#include <cstddef>
#include <vector>

#include "breastfit/core/types.h"

namespace breastfit::io::detail {

/// The triangles of the polygon whose corners, in order, are at `corners` (any number >= 3),
/// as triples of corner positions in the list (0-based), each with the polygon's winding;
/// `triangles` is cleared first (a buffer reused from face to face).
///
/// The polygon is projected onto the plane normal to its Newell normal. When no corner is
/// reflex there (convex, or collinear corners, up to rounding), or the polygon is degenerate (zero Newell
/// normal), the result is the fan (0, i, i+1). Otherwise ears are clipped: a corner whose
/// triangle with its two neighbours turns the polygon's way and contains no other remaining
/// corner is cut off, until three corners remain; should no ear be found (self-intersecting
/// input), the remaining corners are fanned.
void triangulate_polygon(const std::vector<Vec3>& corners,
                         std::vector<std::array<std::size_t, 3>>& triangles);

/// Triangulates index polygons against a flat vertex array (x0 y0 z0 x1 ...), the way the PLY
/// and VTK readers turn their faces into triangles; keeps its buffers from face to face.
class PolygonTriangulator {
 public:
  /// Appends the triangles of the polygon `corners[0..count)` to `tris` (flat, 3 indices per
  /// triangle) as triangulate_polygon cuts it (fan when convex, ear clipping when concave),
  /// skipping triangles that repeat a vertex index. Every corner must index `V` (3 doubles per
  /// vertex); fewer than 3 corners append nothing.
  void append(const std::vector<double>& V, const Index* corners, std::size_t count,
              std::vector<Index>& tris);

 private:
  std::vector<Vec3> positions_;
  std::vector<std::array<std::size_t, 3>> triangles_;
};

}  // namespace breastfit::io::detail
