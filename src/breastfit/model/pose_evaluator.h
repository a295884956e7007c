#pragma once
/// \file Posing of the rigged template and its analytic Jacobians (docs/MODEL.md):
///   B_i = v_i + Σ_k α_k b_ki
///   x_i = Σ_j w_ji ( R_j U_j diag(s_j) U_jᵀ (B_i − c_j) + c_j + t_j )
///   M_i = s_g R_g x_i + t_g
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/surface_point.h"
#include "breastfit/model/param_layout.h"
#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::model {

/// Sparse 3-row Jacobian of one point: entries (parameter index in ParamLayout, ∂M/∂θ ∈ R³),
/// parameter indices unique within one Jacobian.
struct PointJacobian {
  std::vector<int> params;
  std::vector<Vec3> columns;
  void clear() { params.clear(); columns.clear(); }
};

/// Poses the model for a parameter set and answers Jacobian queries for it.
/// Build once per model; call set_params() every solver iteration (O(#V + nnz(blendshapes))).
class PoseEvaluator {
 public:
  /// \pre model.validate() passes. Keeps a reference: the model must outlive the evaluator.
  explicit PoseEvaluator(const RiggedModel& model);

  const RiggedModel& model() const { return model_; }
  const ParamLayout& layout() const { return layout_; }

  /// Poses all vertices for `params` (free when they are bit for bit the current ones).
  void set_params(const PoseParams& params);
  const PoseParams& params() const { return params_; }

  /// Posed vertices M (#V by 3, after the global similarity).
  const Points& vertices() const { return posed_; }
  /// Poses only the vertices `rows` for `params` into the same rows of `out` (#V by 3; the other
  /// rows are left as they are), the same bits as set_params(params) followed by vertices(); the
  /// evaluator itself is not changed. For a caller that reads a few vertices of many parameter
  /// sets (the leave-one-out predictions, landmark_prediction.h): O(#bones + |rows|) per call
  /// instead of O(#V + nnz(blendshapes)).
  void pose_rows(const PoseParams& params, const std::vector<Index>& rows, Points& out) const;
  /// Area-weighted unit normals of the posed mesh.
  Points vertex_normals() const;

  /// Sparse Jacobian of posed vertex i w.r.t. the increment δ of ParamLayout. Entries for the
  /// 7 global parameters, the 9 parameters of each bone with w_ji > 0, and each blendshape moving i
  /// (`with_blendshapes` false: without the blendshapes' entries, for a caller that drops them,
  /// e.g. a stage that does not move them; the other entries are the same).
  void vertex_jacobian(Index i, PointJacobian& out, bool with_blendshapes = true) const;

  /// Position and Jacobian of a surface point (barycentric blend of its triangle's corners).
  Vec3 surface_point(const SurfacePoint& p) const;
  void surface_point_jacobian(const SurfacePoint& p, PointJacobian& out) const;

  /// World position of bone j's pivot as moved by bone `by` (used by joint continuity terms):
  /// G( R_by U diag(s) Uᵀ (c_j − c_by) + c_by + t_by ), and its Jacobian.
  Vec3 pivot_moved_by(int j, int by) const;
  void pivot_moved_by_jacobian(int j, int by, PointJacobian& out) const;

 private:
  const RiggedModel& model_;
  ParamLayout layout_;
  PoseParams params_;
  Points shaped_;   // B (#V by 3)
  Points skinned_;  // x (#V by 3), before the global similarity
  Points posed_;    // M
  std::vector<Mat3> bone_linear_;   // L_j = R_j U_j diag(s_j) U_jᵀ
  std::vector<Mat3> vertex_linear_; // s_g R_g A_i with A_i = Σ_j w_ji L_j (blendshape columns)
  std::vector<Mat3> bone_scale_axes_;  // s_g R_g R_j U_j (bone scale columns)
  Mat3 global_linear_ = Mat3::Identity();  // s_g R_g
  // blendshape incidence (CSR): for vertex i, entries [shape_ptr_[i], shape_ptr_[i+1]) of
  // shape_entries_ are the shapes moving it with its displacement in each (a copy: the Jacobians
  // read them vertex by vertex, in one stream, not from 61 arrays)
  struct ShapeEntry {
    int shape = 0;
    Vec3 displacement = Vec3::Zero();
  };
  std::vector<int> shape_ptr_;
  std::vector<ShapeEntry> shape_entries_;

  // B_i = v_i + Σ α_k b_ki for vertex i (the shapes in ascending order).
  Vec3 shaped_vertex(Index i, const double* alpha) const;
  // x_i = A_i B_i + Σ_j w_ji o_j with A_i = Σ_j w_ji L_j, for the bones' L_j and o_j.
  Vec3 skinned_vertex(Index i, const Vec3& shaped, const std::vector<Mat3>& linear,
                      const std::vector<Vec3>& offset, Mat3& A) const;

  void append_global(const Vec3& x, PointJacobian& out) const;
  void append_bone(int j, double w, const Vec3& d, PointJacobian& out) const;
};

/// One-call posing: posed vertices of `model` for `params`.
Points pose_vertices(const RiggedModel& model, const PoseParams& params);

}  // namespace breastfit::model
