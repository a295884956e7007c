// The reverse data term (beyond the paper): scan sample → closest point on the posed model,
// point-to-plane, averaged over the kept samples. It pulls the model into parts of the scan that
// no model vertex claims (e.g. a breast larger than the template's):
//   E_R = 1/λR · 1/|S| Σ_{p∈S} w_p (n_p·(X_p(θ) − s_p))²
// Used in the stages that move blendshapes; λR ≤ 0 disables it.
#include "breastfit/fit/energy_term.h"

#include "breastfit/fit/chunked_assembly.h"
#include "breastfit/fit/fit_options.h"

namespace breastfit::fit {
namespace {

class ReverseTerm final : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;
};

double ReverseTerm::evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const {
  if (ctx.reverse.empty()) return 0.0;
  const double scale = weight / static_cast<double>(ctx.reverse.size());
  const Triangles& F = ctx.ev.model().rest.F;
  const auto rows = [&](Index begin, Index end, NormalEquations* part) {
    double cost = 0.0;
    model::PointJacobian jac;
    std::vector<double> vals;
    for (Index k = begin; k < end; ++k) {
      const ReverseCorrespondence& c = ctx.reverse[static_cast<size_t>(k)];
      const Vec3 d = ctx.ev.surface_point(c.model_point) - c.source;
      const double w = scale * c.weight;
      const double r = c.normal.dot(d);
      cost += w * r * r;
      if (!part) continue;
      // The row is Σ_corners bary_c · nᵀ ∂M_c/∂θ: assembled corner by corner (no merging).
      part->begin_row(r, w);
      for (int corner = 0; corner < 3; ++corner) {
        ctx.ev.vertex_jacobian(F(c.model_point.face, corner), jac);
        const int nnz = static_cast<int>(jac.params.size());
        vals.resize(nnz);
        for (int j = 0; j < nnz; ++j) vals[j] = c.normal.dot(jac.columns[j]);
        part->add_to_row(jac.params.data(), vals.data(), nnz, c.model_point.bary[corner]);
      }
      part->end_row();
    }
    return cost;
  };
  return assemble_in_chunks(static_cast<Index>(ctx.reverse.size()), ctx.options.threads, eq, rows);
}

}  // namespace

TermSpec reverse_term_spec() {
  return {"reverse", "λR", 2.0, "mm²", "reverse data term: scan → model, mean squared point-to-plane distance",
          true, [] { return std::unique_ptr<EnergyTerm>(new ReverseTerm); }};
}

}  // namespace breastfit::fit
