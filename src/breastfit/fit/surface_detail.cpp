#include "breastfit/fit/surface_detail.h"

#include <algorithm>
#include <array>
#include <memory>
#include <cmath>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "breastfit/core/errors.h"
#include "breastfit/fit/correspondences.h"
#include "breastfit/fit/detail_system.h"
#include "breastfit/mesh/normals.h"

namespace breastfit::fit {
namespace {

// V + h · N, row by row.
Points displaced(const Points& V, const Points& N, const Eigen::VectorXd& h) {
  return (V.array() + N.array().colwise() * h.array()).matrix();
}

}  // namespace

Points apply_surface_detail(const Points& V, const Triangles& F, const Eigen::VectorXd& offsets) {
  if (offsets.size() != V.rows())
    throw InvalidInput("surface detail has " + std::to_string(offsets.size()) + " offsets for " +
                       std::to_string(V.rows()) + " vertices");
  const Points N = mesh::vertex_normals(V, F);
  return displaced(V, N, offsets);
}

SurfaceDetail fit_surface_detail(const Points& V, const Triangles& F, const ScanTarget& scan,
                                 const CorrespondenceOptions& correspondences, const SurfaceDetailOptions& o,
                                 int threads, const DetailFirstPass* first) {
  const Index n = V.rows();
  SurfaceDetail out;
  out.offsets = Eigen::VectorXd::Zero(n);
  out.vertices = V;
  if (!o.enabled || o.passes <= 0 || n == 0) return out;

  const Points N = mesh::vertex_normals(V, F);
  // μ · graph Laplacian + ε · I: fixed over the passes (and over the fits of the same template:
  // leased, fit/detail_system.h); the data weights change the diagonal only.
  const std::shared_ptr<DetailSystem> system = lease_detail_system(F, n, o.smoothness, o.decay);
  Eigen::SparseMatrix<double>& A = system->A;
  const Eigen::VectorXd& base_diag = system->base_diag;
  auto& solver = system->solver;

  // The pairs' own IRLS weights (of the distance before any offset) are not used: the weights
  // below come from the residual the previous pass left.
  std::vector<Index> hints(n, -1);
  if (first && static_cast<Index>(first->hints.size()) == n) hints = first->hints;
  Eigen::VectorXd h = Eigen::VectorXd::Zero(n);
  for (int pass = 0; pass < o.passes; ++pass) {
    std::vector<Correspondence> searched;
    if (!(first && pass == 0)) {
      CorrespondenceStats st;
      searched = find_correspondences(displaced(V, N, h), N, scan, correspondences, o.max_distance_mm, 1, &st, &hints,
                                      threads);
    }
    const std::vector<Correspondence>& pairs = first && pass == 0 ? first->pairs : searched;
    Eigen::VectorXd diag = base_diag;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    for (const auto& c : pairs) {
      const Vec3 ni = N.row(c.vertex).transpose();
      const double cosang = ni.dot(c.normal);
      if (cosang < 0.2) continue;  // only with a normal-angle limit beyond ~78° (default 60°)
      // Offset along n_i that puts the vertex on the scan's tangent plane at the match.
      const double r = c.normal.dot(c.target - V.row(c.vertex).transpose()) / cosang;
      const double w = pass == 0 ? 1.0 : robust_weight(RobustKernel::GemanMcClure, r - h[c.vertex], o.kernel_scale_mm);
      diag[c.vertex] += w;
      rhs[c.vertex] += w * r;
    }
    out.kept = static_cast<int>(pairs.size());
    for (Index i = 0; i < n; ++i) A.coeffRef(i, i) = diag[i];
    solver.factorize(A);
    if (solver.info() != Eigen::Success) break;  // cannot happen (A is SPD for ε > 0); keep the last offsets
    h = solver.solve(rhs).cwiseMax(-o.max_offset_mm).cwiseMin(o.max_offset_mm);
  }
  out.offsets = h;
  out.vertices = displaced(V, N, h);
  out.mean_abs_mm = h.cwiseAbs().mean();
  out.max_abs_mm = h.cwiseAbs().maxCoeff();
  return out;
}

}  // namespace breastfit::fit
