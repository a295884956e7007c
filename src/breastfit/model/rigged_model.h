#pragma once
/// \file The rigged template: rest mesh, scalable bones, skin weights, bounded blendshapes,
/// landmarks and drawings stored as surface points (paper §2.4–2.6, docs/MODEL.md).
#include <optional>
#include <string>
#include <vector>

#include <Eigen/SparseCore>

#include "breastfit/core/types.h"
#include "breastfit/mesh/surface_point.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::model {

/// One scalable bone. Rotation and scale act about `pivot`; scale acts along the columns of `axes`.
struct Bone {
  std::string name;
  std::optional<int> parent;   ///< index of the parent bone; nullopt for the root
  Vec3 pivot = Vec3::Zero();   ///< joint point with the parent (bone centre for the root), mm
  Mat3 axes = Mat3::Identity();  ///< rest axes, orthonormal columns, right-handed
  Vec3 scale_lo = Vec3::Constant(0.5);  ///< lower bound of each scale (> 0)
  Vec3 scale_hi = Vec3::Constant(2.0);  ///< upper bound of each scale
  /// Per-axis weight of the scale prior E_S (1 = the fit's λS; > 1 = stiffer). The template's
  /// anatomy knowledge: e.g. a breast's base on the chest wall varies less between women than
  /// its projection, so the breast bones' in-plane scales are stiffer (template_skeleton.cpp).
  Vec3 scale_stiffness = Vec3::Ones();
};

/// A named linear shape: displacement (mm at weight 1) of a sparse set of vertices.
struct Blendshape {
  std::string name;
  std::vector<Index> vertices;   ///< the vertices it moves (ascending, unique)
  Points displacements;          ///< #vertices by 3 displacement at weight 1, mm
  double lo = -1.0;              ///< lower bound of the weight
  double hi = 1.0;               ///< upper bound of the weight
};

/// A named point on the template surface.
struct ModelLandmark {
  std::string name;
  SurfacePoint point;
};

/// A named polyline on the template surface (a surgical drawing).
struct Drawing {
  std::string name;
  bool closed = false;
  std::vector<SurfacePoint> points;
};

/// A named set of vertices (e.g. breast_R) used for measurements and reports.
struct VertexRegion {
  std::string name;
  std::vector<Index> vertices;
};

/// Row-major sparse skin weights: #V rows by #bones columns, rows non-negative and summing to 1.
using SkinWeights = Eigen::SparseMatrix<double, Eigen::RowMajor, Index>;

struct RiggedModel {
  std::string name = "template";
  TriangleMesh rest;                 ///< rest mesh (V, F), mm, body frame LPS
  std::vector<Bone> bones;           ///< parents come before children
  SkinWeights weights;               ///< #V by #bones
  std::vector<Blendshape> blendshapes;
  std::vector<ModelLandmark> landmarks;
  std::vector<Drawing> drawings;
  std::vector<VertexRegion> regions;

  int num_bones() const { return static_cast<int>(bones.size()); }
  int num_blendshapes() const { return static_cast<int>(blendshapes.size()); }
  Index num_vertices() const { return rest.num_vertices(); }

  /// Index of a bone / blendshape / landmark / drawing / region by name, or nullopt.
  std::optional<int> bone_index(const std::string& name) const;
  std::optional<int> blendshape_index(const std::string& name) const;
  std::optional<int> landmark_index(const std::string& name) const;
  std::optional<int> drawing_index(const std::string& name) const;
  std::optional<int> region_index(const std::string& name) const;

  /// The vertices `bone` mostly moves: skin weight above `min_weight` (0.6: the upper arm's own
  /// vertices, not the shoulder's blend), ascending.
  std::vector<Index> vertices_mostly_moved_by(int bone, double min_weight = 0.6) const;

  /// Checks every invariant (sizes, finite values, weights normalised, parents before children,
  /// bounds ordered, surface points valid, axes orthonormal).
  /// \throws InvalidInput naming the first violation.
  void validate() const;
};

}  // namespace breastfit::model
