#include "breastfit/fit/priors.h"

#include "breastfit/core/so3.h"

namespace breastfit::fit {
namespace {

// One scalar residual r with a dense Jacobian block: row = Σ_a J(a) δ_{offset_a}.
void add_vector_residual(const Vec3& r, const std::vector<std::pair<int, Mat3>>& blocks, double w,
                         NormalEquations& eq) {
  int idx[64];
  double val[64];
  for (int axis = 0; axis < 3; ++axis) {
    int nnz = 0;
    for (const auto& [offset, J] : blocks)
      for (int c = 0; c < 3; ++c) {
        idx[nnz] = offset + c;
        val[nnz] = J(axis, c);
        ++nnz;
      }
    eq.add_row(idx, val, nnz, r[axis], w);
  }
}

}  // namespace

PriorCosts add_priors(const model::PoseEvaluator& ev, const PriorScales& s, NormalEquations* eq) {
  const auto& model = ev.model();
  const auto& layout = ev.layout();
  const auto& p = ev.params();
  PriorCosts cost;

  for (int j = 0; j < model.num_bones(); ++j) {
    const auto& bp = p.bones[j];
    const int off = layout.bone_offset(j);
    // E_S, weighted per axis by the template's stiffness
    for (int a = 0; a < 3; ++a) {
      const double r = bp.scale[a] - 1.0;
      const double w = s.scale * model.bones[j].scale_stiffness[a];
      cost.scale += w * r * r;
      if (eq) {
        const int idx = off + 6 + a;
        const double one = 1.0;
        eq->add_row(&idx, &one, 1, r, w);
      }
    }
    // E_J rotation relative to the parent
    const auto parent = model.bones[j].parent;
    const Quat Rp = parent ? p.bones[*parent].rotation : Quat::Identity();
    const Vec3 phi = log_so3(Rp.conjugate() * bp.rotation);
    cost.joint += s.joint * phi.squaredNorm();
    if (eq) {
      const Mat3 Jinv = left_jacobian_inverse(phi) * Rp.conjugate().toRotationMatrix();
      std::vector<std::pair<int, Mat3>> blocks{{off, Jinv}};
      if (parent) blocks.push_back({layout.bone_offset(*parent), -Jinv});
      add_vector_residual(phi, blocks, s.joint, *eq);
    }
    if (!parent) {
      const Vec3 r = bp.translation / s.joint_translation_scale_mm;
      cost.joint += s.joint * r.squaredNorm();
      if (eq) {
        const Mat3 J = Mat3::Identity() / s.joint_translation_scale_mm;
        add_vector_residual(r, {{off + 3, J}}, s.joint, *eq);
      }
    } else {
      // E_C: the joint point moved by the child and by the parent coincide.
      const Vec3 r = ev.pivot_moved_by(j, j) - ev.pivot_moved_by(j, *parent);
      cost.continuity += s.continuity * r.squaredNorm();
      if (eq) {
        model::PointJacobian a, b;
        ev.pivot_moved_by_jacobian(j, j, a);
        ev.pivot_moved_by_jacobian(j, *parent, b);
        // merge a − b into one sparse set of columns
        std::vector<int> idx = a.params;
        std::vector<Vec3> cols = a.columns;
        for (size_t k = 0; k < b.params.size(); ++k) {
          bool found = false;
          for (size_t m = 0; m < idx.size(); ++m)
            if (idx[m] == b.params[k]) {
              cols[m] -= b.columns[k];
              found = true;
            }
          if (!found) {
            idx.push_back(b.params[k]);
            cols.push_back(-b.columns[k]);
          }
        }
        std::vector<double> val(idx.size());
        for (int axis = 0; axis < 3; ++axis) {
          for (size_t k = 0; k < idx.size(); ++k) val[k] = cols[k][axis];
          eq->add_row(idx.data(), val.data(), static_cast<int>(idx.size()), r[axis], s.continuity);
        }
      }
    }
  }
  // E_BS
  for (int k = 0; k < model.num_blendshapes(); ++k) {
    const double a = p.alpha[k];
    cost.blendshape += s.blendshape * a * a;
    if (eq) {
      const int idx = layout.blendshape_offset(k);
      const double one = 1.0;
      eq->add_row(&idx, &one, 1, a, s.blendshape);
    }
  }
  return cost;
}

}  // namespace breastfit::fit
