#pragma once
/// \file The triangle mesh (or point cloud, when it has no faces) used everywhere.
#include "breastfit/core/types.h"

namespace breastfit {

/// Vertices and triangles plus optional per-vertex attributes.
/// A mesh with no faces is a point cloud. Coordinates are millimetres once inside the library.
struct TriangleMesh {
  Points V;              ///< #V by 3 vertex positions
  Triangles F;           ///< #F by 3 vertex indices (counter-clockwise = outward)
  Points N;              ///< #V by 3 vertex normals, or empty
  Colors C;              ///< #V by 3 RGB colours, or empty
  TexCoords UV;          ///< #T by 2 texture coordinates, or empty
  Triangles FUV;         ///< #F by 3 indices into UV (per face corner), or empty

  Index num_vertices() const { return static_cast<Index>(V.rows()); }
  Index num_faces() const { return static_cast<Index>(F.rows()); }
  bool is_point_cloud() const { return F.rows() == 0; }
  bool has_normals() const { return N.rows() == V.rows() && N.rows() > 0; }
  bool has_colors() const { return C.rows() == V.rows() && C.rows() > 0; }
  bool has_texcoords() const { return UV.rows() > 0 && FUV.rows() == F.rows(); }
};

}  // namespace breastfit
