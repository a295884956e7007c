#include "breastfit/model/pose_evaluator.h"

#include <algorithm>
#include <cstring>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/normals.h"

namespace breastfit::model {
namespace {

/// e_m × y for m = 0..2 are the columns of −[y]×.
inline Vec3 unit_cross(int m, const Vec3& y) {
  switch (m) {
    case 0: return Vec3(0.0, -y.z(), y.y());
    case 1: return Vec3(y.z(), 0.0, -y.x());
    default: return Vec3(-y.y(), y.x(), 0.0);
  }
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// One bone's pose: R_j U_j, L_j = R_j U_j diag(s_j) U_jᵀ and o_j = c_j + t_j − L_j c_j, so that
/// L_j (B − c_j) + c_j + t_j = L_j B + o_j.
struct BoneTransform {
  Mat3 rotated_axes, linear;
  Vec3 offset;
};

void require_model_params(const RiggedModel& m, const PoseParams& params) {
  if (static_cast<int>(params.bones.size()) != m.num_bones() || params.alpha.size() != m.num_blendshapes())
    throw InvalidInput("pose evaluator: parameters have " + std::to_string(params.bones.size()) + " bones and " +
                       std::to_string(params.alpha.size()) + " blendshape weights, the model has " +
                       std::to_string(m.num_bones()) + " and " + std::to_string(m.num_blendshapes()));
}

BoneTransform bone_transform(const Bone& b, const BonePose& p) {
  BoneTransform t;
  t.rotated_axes = p.rotation.toRotationMatrix() * b.axes;
  t.linear = t.rotated_axes * p.scale.asDiagonal() * b.axes.transpose();
  t.offset = b.pivot + p.translation - t.linear * b.pivot;
  return t;
}

template <class M>
bool same_bits(const M& a, const M& b) {
  if (a.size() != b.size()) return false;
  for (Eigen::Index k = 0; k < a.size(); ++k)
    if (!same_bits(a.data()[k], b.data()[k])) return false;
  return true;
}

bool same_bits(const Quat& a, const Quat& b) { return same_bits(a.coeffs(), b.coeffs()); }

// Bit for bit the same parameters (so the same posed mesh: set_params may keep it).
bool same_params(const PoseParams& a, const PoseParams& b) {
  if (a.bones.size() != b.bones.size() || !same_bits(a.alpha, b.alpha)) return false;
  if (!same_bits(a.global.rotation, b.global.rotation) || !same_bits(a.global.translation, b.global.translation) ||
      !same_bits(a.global.scale, b.global.scale))
    return false;
  for (size_t j = 0; j < a.bones.size(); ++j)
    if (!same_bits(a.bones[j].rotation, b.bones[j].rotation) ||
        !same_bits(a.bones[j].translation, b.bones[j].translation) || !same_bits(a.bones[j].scale, b.bones[j].scale))
      return false;
  return true;
}

}  // namespace

PoseEvaluator::PoseEvaluator(const RiggedModel& model) : model_(model), layout_(model) {
  const Index nv = model.num_vertices();
  if (model.weights.rows() != nv || model.weights.cols() != model.num_bones())
    throw InvalidInput("pose evaluator: skin weights do not match the model (run RiggedModel::validate())");
  // Blendshape incidence in CSR form, shapes in ascending order per vertex.
  std::vector<int> counts(static_cast<size_t>(nv) + 1, 0);
  for (const auto& s : model.blendshapes) {
    for (Index v : s.vertices) {
      if (v < 0 || v >= nv) throw InvalidInput("pose evaluator: blendshape '" + s.name + "' vertex out of range");
      ++counts[v + 1];
    }
  }
  shape_ptr_.assign(static_cast<size_t>(nv) + 1, 0);
  for (Index i = 0; i < nv; ++i) shape_ptr_[i + 1] = shape_ptr_[i] + counts[i + 1];
  shape_entries_.resize(shape_ptr_[nv]);
  std::vector<int> fill(shape_ptr_.begin(), shape_ptr_.end() - 1);
  for (int k = 0; k < model.num_blendshapes(); ++k) {
    const auto& verts = model.blendshapes[k].vertices;
    for (size_t r = 0; r < verts.size(); ++r)
      shape_entries_[fill[verts[r]]++] = {k, model.blendshapes[k].displacements.row(r).transpose()};
  }
  bone_linear_.resize(model.bones.size());
  bone_scale_axes_.resize(model.bones.size());
  vertex_linear_.resize(nv);
  set_params(PoseParams::identity(model));
}

void PoseEvaluator::set_params(const PoseParams& params) {
  const RiggedModel& m = model_;
  require_model_params(m, params);
  // The solver sets the same parameters again (after an accepted step, at a stage's start and
  // end): the posed mesh is already theirs.
  if (posed_.rows() == m.num_vertices() && same_params(params, params_)) return;
  // The stages that move only the pose (landmark_pose, rigid, pose) keep the blendshape weights:
  // their shaped mesh is the one already here.
  const bool same_shape = shaped_.rows() == m.num_vertices() && same_bits(params.alpha, params_.alpha);
  params_ = params;
  const Index nv = m.num_vertices();

  // B = v + Σ α_k b_k, vertex by vertex from the incidence (the shapes in ascending order, as a
  // pass per shape would add them).
  if (!same_shape) {
    shaped_.resize(nv, 3);
    for (Index i = 0; i < nv; ++i) shaped_.row(i) = shaped_vertex(i, params.alpha.data()).transpose();
  }

  global_linear_ = params.global.scale * params.global.rotation.toRotationMatrix();
  std::vector<Vec3> offset(m.bones.size());
  for (int j = 0; j < m.num_bones(); ++j) {
    const BoneTransform t = bone_transform(m.bones[j], params.bones[j]);
    bone_linear_[j] = t.linear;
    bone_scale_axes_[j] = global_linear_ * t.rotated_axes;
    offset[j] = t.offset;
  }

  skinned_.resize(nv, 3);
  posed_.resize(nv, 3);
  const Vec3 tg = params.global.translation;
  for (Index i = 0; i < nv; ++i) {
    Mat3 A;
    const Vec3 x = skinned_vertex(i, shaped_.row(i).transpose(), bone_linear_, offset, A);
    skinned_.row(i) = x.transpose();
    posed_.row(i) = (global_linear_ * x + tg).transpose();
    vertex_linear_[i].noalias() = global_linear_ * A;
  }
}

Vec3 PoseEvaluator::shaped_vertex(Index i, const double* alpha) const {
  Vec3 b = model_.rest.V.row(i).transpose();
  for (int e = shape_ptr_[i]; e < shape_ptr_[i + 1]; ++e) {
    const double a = alpha[shape_entries_[e].shape];
    if (a != 0.0) b += a * shape_entries_[e].displacement;
  }
  return b;
}

Vec3 PoseEvaluator::skinned_vertex(Index i, const Vec3& shaped, const std::vector<Mat3>& linear,
                                   const std::vector<Vec3>& offset, Mat3& A) const {
  A = Mat3::Zero();
  Vec3 o = Vec3::Zero();
  for (SkinWeights::InnerIterator it(model_.weights, i); it; ++it) {
    const double w = it.value();
    A.noalias() += w * linear[it.col()];
    o.noalias() += w * offset[it.col()];
  }
  return A * shaped + o;
}

void PoseEvaluator::pose_rows(const PoseParams& params, const std::vector<Index>& rows, Points& out) const {
  const RiggedModel& m = model_;
  require_model_params(m, params);
  if (out.rows() != m.num_vertices()) throw InvalidInput("pose evaluator: pose_rows needs #V rows to write into");
  // The same helpers as set_params: the same roundings.
  const Mat3 global_linear = params.global.scale * params.global.rotation.toRotationMatrix();
  std::vector<Mat3> linear(m.bones.size());
  std::vector<Vec3> offset(m.bones.size());
  for (int j = 0; j < m.num_bones(); ++j) {
    const BoneTransform t = bone_transform(m.bones[j], params.bones[j]);
    linear[j] = t.linear;
    offset[j] = t.offset;
  }
  const Vec3 tg = params.global.translation;
  for (Index i : rows) {
    if (i < 0 || i >= m.num_vertices()) throw InvalidInput("pose evaluator: vertex " + std::to_string(i) + " out of range");
    Mat3 A;
    const Vec3 x = skinned_vertex(i, shaped_vertex(i, params.alpha.data()), linear, offset, A);
    out.row(i) = (global_linear * x + tg).transpose();
  }
}

Points PoseEvaluator::vertex_normals() const { return mesh::vertex_normals(posed_, model_.rest.F); }

void PoseEvaluator::append_global(const Vec3& x, PointJacobian& out) const {
  // M = s_g R_g x + t_g;  ∂M/∂ω_g = −[s_g R_g x]×, ∂M/∂t_g = I, ∂M/∂(log s_g) = s_g R_g x.
  const Vec3 y = global_linear_ * x;
  for (int m = 0; m < 3; ++m) {
    out.params.push_back(m);
    out.columns.push_back(unit_cross(m, y));
  }
  for (int m = 0; m < 3; ++m) {
    out.params.push_back(3 + m);
    out.columns.push_back(Vec3::Unit(m));
  }
  out.params.push_back(6);
  out.columns.push_back(y);
}

void PoseEvaluator::append_bone(int j, double w, const Vec3& d, PointJacobian& out) const {
  // d = B − c_j.  ∂x/∂ω_j = −w [L_j d]×,  ∂x/∂t_j = w I,  ∂x/∂s_j(a) = w R_j U_j e_a e_aᵀ U_jᵀ d;
  // all chained through G: ∂M = s_g R_g ∂x.
  const int o = layout_.bone_offset(j);
  const Vec3 y = bone_linear_[j] * d;
  for (int m = 0; m < 3; ++m) {
    out.params.push_back(o + m);
    out.columns.push_back(w * (global_linear_ * unit_cross(m, y)));
  }
  for (int m = 0; m < 3; ++m) {
    out.params.push_back(o + 3 + m);
    out.columns.push_back(w * global_linear_.col(m));
  }
  const Mat3& U = model_.bones[j].axes;
  for (int a = 0; a < 3; ++a) {
    out.params.push_back(o + 6 + a);
    out.columns.push_back((w * U.col(a).dot(d)) * bone_scale_axes_[j].col(a));
  }
}

void PoseEvaluator::vertex_jacobian(Index i, PointJacobian& out, bool with_blendshapes) const {
  out.clear();
  append_global(skinned_.row(i).transpose(), out);
  const Vec3 B = shaped_.row(i).transpose();
  for (SkinWeights::InnerIterator it(model_.weights, i); it; ++it) {
    if (it.value() <= 0.0) continue;
    const int j = static_cast<int>(it.col());
    append_bone(j, it.value(), B - model_.bones[j].pivot, out);
  }
  if (!with_blendshapes) return;
  const Mat3& GA = vertex_linear_[i];
  const int base = layout_.blendshape_offset(0);
  for (int e = shape_ptr_[i]; e < shape_ptr_[i + 1]; ++e) {
    const ShapeEntry& entry = shape_entries_[e];
    out.params.push_back(base + entry.shape);
    out.columns.push_back(GA * entry.displacement);
  }
}

Vec3 PoseEvaluator::surface_point(const SurfacePoint& p) const {
  if (p.face < 0 || p.face >= model_.rest.num_faces())
    throw InvalidInput("surface point face " + std::to_string(p.face) + " out of range");
  return p.position(posed_, model_.rest.F);
}

void PoseEvaluator::surface_point_jacobian(const SurfacePoint& p, PointJacobian& out) const {
  if (p.face < 0 || p.face >= model_.rest.num_faces())
    throw InvalidInput("surface point face " + std::to_string(p.face) + " out of range");
  std::vector<std::pair<int, Vec3>> entries;
  PointJacobian corner;
  for (int c = 0; c < 3; ++c) {
    if (p.bary[c] == 0.0) continue;
    vertex_jacobian(model_.rest.F(p.face, c), corner);
    for (size_t e = 0; e < corner.params.size(); ++e)
      entries.emplace_back(corner.params[e], p.bary[c] * corner.columns[e]);
  }
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  out.clear();
  for (const auto& [param, col] : entries) {
    if (!out.params.empty() && out.params.back() == param) {
      out.columns.back() += col;
    } else {
      out.params.push_back(param);
      out.columns.push_back(col);
    }
  }
}

namespace {
void check_bone_pair(const RiggedModel& m, int j, int by) {
  if (j < 0 || j >= m.num_bones() || by < 0 || by >= m.num_bones())
    throw InvalidInput("pivot_moved_by: bone index out of range (" + std::to_string(j) + ", " + std::to_string(by) +
                       ") for " + std::to_string(m.num_bones()) + " bones");
}
}  // namespace

Vec3 PoseEvaluator::pivot_moved_by(int j, int by) const {
  check_bone_pair(model_, j, by);
  const Vec3& cb = model_.bones[by].pivot;
  const Vec3 x = bone_linear_[by] * (model_.bones[j].pivot - cb) + cb + params_.bones[by].translation;
  return global_linear_ * x + params_.global.translation;
}

void PoseEvaluator::pivot_moved_by_jacobian(int j, int by, PointJacobian& out) const {
  check_bone_pair(model_, j, by);
  const Vec3& cb = model_.bones[by].pivot;
  const Vec3 d = model_.bones[j].pivot - cb;
  const Vec3 x = bone_linear_[by] * d + cb + params_.bones[by].translation;
  out.clear();
  append_global(x, out);
  append_bone(by, 1.0, d, out);
}

Points pose_vertices(const RiggedModel& model, const PoseParams& params) {
  PoseEvaluator e(model);
  e.set_params(params);
  return e.vertices();
}

}  // namespace breastfit::model
