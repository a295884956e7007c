// Joint regulariser (paper eq. 7): each bone's rotation relative to its parent (the root's
// relative to the global similarity), and the root bone's translation over τ:
//   E_J = 1/λJ · [ Σ_j ‖log(R_parent(j)ᵀ R_j)‖² + ‖t_root / τ‖² ]
// τ = EnergyWeights::joint_translation_scale_mm. Child translations are tied to their parent by
// the continuity term instead (continuity_term.cpp).
#include "breastfit/fit/energy_term.h"

#include "breastfit/core/so3.h"
#include "breastfit/fit/fit_options.h"

namespace breastfit::fit {
namespace {

class JointPrior final : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;
};
namespace {

// The three rows of a vector residual r whose Jacobian is a sum of dense 3×3 blocks, each on
// three consecutive parameters starting at its offset.
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

double JointPrior::evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const {
  const auto& model = ctx.ev.model();
  const auto& layout = ctx.ev.layout();
  const auto& p = ctx.ev.params();
  const double tau = ctx.options.weights.joint_translation_scale_mm;
  double cost = 0.0;
  for (int j = 0; j < model.num_bones(); ++j) {
    const auto& bp = p.bones[j];
    const int off = layout.bone_offset(j);
    const auto parent = model.bones[j].parent;
    const Quat Rp = parent ? p.bones[*parent].rotation : Quat::Identity();
    const Vec3 phi = log_so3(Rp.conjugate() * bp.rotation);
    cost += weight * phi.squaredNorm();
    if (eq) {
      const Mat3 Jinv = left_jacobian_inverse(phi) * Rp.conjugate().toRotationMatrix();
      std::vector<std::pair<int, Mat3>> blocks{{off, Jinv}};
      if (parent) blocks.push_back({layout.bone_offset(*parent), -Jinv});
      add_vector_residual(phi, blocks, weight, *eq);
    }
    if (parent) continue;
    const Vec3 r = bp.translation / tau;
    cost += weight * r.squaredNorm();
    if (eq) add_vector_residual(r, {{off + 3, Mat3::Identity() / tau}}, weight, *eq);
  }
  return cost;
}

}  // namespace

TermSpec joint_prior_spec() {
  return {"joints", "λJ", 1.0, "rad², (mm/τ)²", "joint regulariser E_J", false,
          [] { return std::unique_ptr<EnergyTerm>(new JointPrior); }};
}

}  // namespace breastfit::fit
