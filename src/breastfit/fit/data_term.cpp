// The data term (paper eq. 8): model vertex → closest scan point, point-to-plane mixed with
// point-to-point, robust IRLS weights, averaged over the kept correspondences:
//   E_D = 1/λD · 1/|C| Σ_{c∈C} w_c [(1−μ)(n_c·(M_i − p_c))² + μ‖M_i − p_c‖²]
#include "breastfit/fit/energy_term.h"

#include <algorithm>

#include "breastfit/fit/chunked_assembly.h"
#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/row_builder.h"

namespace breastfit::fit {
namespace {

class DataTerm final : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;
};

double DataTerm::evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const {
  const Points& M = ctx.ev.vertices();
  const double mu = ctx.options.correspondences.point_to_point_weight;
  const double scale = weight / static_cast<double>(std::max<size_t>(1, ctx.pairs.size()));
  const model::ParamLayout& layout = ctx.ev.layout();
  const auto rows = [&](Index begin, Index end, NormalEquations* part) {
    double cost = 0.0;
    model::PointJacobian jac;
    std::vector<double> vals;
    // A stage that does not move the blendshapes drops their entries: not computed.
    const bool shapes = part && part->any_active(layout.blendshape_offset(0), layout.num_params());
    for (Index k = begin; k < end; ++k) {
      const Correspondence& c = ctx.pairs[static_cast<size_t>(k)];
      const Vec3 d = M.row(c.vertex).transpose() - c.target;
      const double w_plane = scale * c.weight * (1.0 - mu);
      const double w_point = scale * c.weight * mu;
      const double r = c.normal.dot(d);
      cost += w_plane * r * r + w_point * d.squaredNorm();
      if (!part) continue;
      ctx.ev.vertex_jacobian(c.vertex, jac, shapes);
      if (w_plane > 0) add_plane_row(jac, d, c.normal, w_plane, *part, vals);
      if (w_point > 0) add_point_rows(jac, d, w_point, *part, vals);
    }
    return cost;
  };
  return assemble_in_chunks(static_cast<Index>(ctx.pairs.size()), ctx.options.threads, eq, rows);
}

}  // namespace

TermSpec data_term_spec() {
  return {"data", "λD", 0.25, "mm²", "data term: model → scan, mean squared point-to-plane distance", false,
          [] { return std::unique_ptr<EnergyTerm>(new DataTerm); }};
}

}  // namespace breastfit::fit
