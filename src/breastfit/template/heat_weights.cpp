#include "breastfit/template/heat_weights.h"

#include <algorithm>
#include <numeric>
#include <vector>

#include <Eigen/SparseCholesky>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/normals.h"

namespace breastfit::templ {

Eigen::SparseMatrix<double> cotan_laplacian(const TriangleMesh& mesh) {
  const Index nv = mesh.num_vertices();
  std::vector<Eigen::Triplet<double>> T;
  T.reserve(static_cast<size_t>(mesh.num_faces()) * 12);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const Index i = mesh.F(f, c), j = mesh.F(f, (c + 1) % 3), k = mesh.F(f, (c + 2) % 3);
      const Vec3 a = mesh.V.row(i) - mesh.V.row(k);
      const Vec3 b = mesh.V.row(j) - mesh.V.row(k);
      const double cr = a.cross(b).norm();
      double cot = cr > 1e-12 ? a.dot(b) / cr : 0.0;
      cot = std::clamp(cot, -5.0, 5.0);
      const double w = 0.5 * cot;
      T.emplace_back(i, j, w);
      T.emplace_back(j, i, w);
      T.emplace_back(i, i, -w);
      T.emplace_back(j, j, -w);
    }
  }
  Eigen::SparseMatrix<double> L(nv, nv);
  L.setFromTriplets(T.begin(), T.end());
  return L;
}

Eigen::VectorXd vertex_areas(const TriangleMesh& mesh) {
  Eigen::VectorXd A = Eigen::VectorXd::Zero(mesh.num_vertices());
  const Eigen::VectorXd face_area = mesh::face_areas(mesh);
  for (Index f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) A[mesh.F(f, k)] += face_area[f] / 3.0;
  return A;
}

Eigen::MatrixXd diffuse(const TriangleMesh& mesh, const Eigen::MatrixXd& values, double t) {
  if (values.rows() != mesh.num_vertices()) throw InvalidInput("diffuse: one row per vertex needed");
  if (!(t >= 0)) throw InvalidInput("diffuse: time must be >= 0");
  const Eigen::VectorXd A = vertex_areas(mesh);
  Eigen::SparseMatrix<double> M(mesh.num_vertices(), mesh.num_vertices());
  std::vector<Eigen::Triplet<double>> T;
  for (Index v = 0; v < mesh.num_vertices(); ++v) T.emplace_back(v, v, std::max(A[v], 1e-9));
  M.setFromTriplets(T.begin(), T.end());
  const Eigen::SparseMatrix<double> S = M - t * cotan_laplacian(mesh);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(S);
  if (solver.info() != Eigen::Success) throw InvalidInput("diffuse: factorisation failed");
  Eigen::MatrixXd rhs = M * values;
  return solver.solve(rhs);
}

model::SkinWeights heat_diffusion_weights(const TriangleMesh& mesh, const Eigen::MatrixXd& seeds,
                                          const HeatWeightOptions& o) {
  if (seeds.rows() != mesh.num_vertices()) throw InvalidInput("heat_diffusion_weights: one seed row per vertex");
  if (o.max_influences < 1) throw InvalidInput("heat_diffusion_weights: max_influences must be >= 1");
  const Eigen::MatrixXd W = diffuse(mesh, seeds, o.diffusion_time_mm2);
  const Index nb = static_cast<Index>(seeds.cols());
  std::vector<Eigen::Triplet<double, Index>> T;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    std::vector<std::pair<double, Index>> w;
    double sum = 0;
    for (Index j = 0; j < nb; ++j) sum += std::max(W(v, j), 0.0);
    for (Index j = 0; j < nb; ++j) {
      const double x = sum > 0 ? std::max(W(v, j), 0.0) / sum : 0.0;
      w.emplace_back(x, j);
    }
    std::stable_sort(w.begin(), w.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    double kept = 0;
    int n = 0;
    for (const auto& [x, j] : w) {
      if (n >= o.max_influences || (n > 0 && x < o.prune_below)) break;
      kept += x;
      ++n;
    }
    if (kept <= 0) throw InvalidInput("heat_diffusion_weights: vertex " + std::to_string(v) + " has no weight");
    std::vector<std::pair<Index, double>> row;
    for (int k = 0; k < n; ++k) row.emplace_back(w[k].second, w[k].first / kept);
    std::sort(row.begin(), row.end());
    for (const auto& [j, x] : row) T.emplace_back(v, j, x);
  }
  model::SkinWeights S(mesh.num_vertices(), nb);
  S.setFromTriplets(T.begin(), T.end());
  S.makeCompressed();
  return S;
}

}  // namespace breastfit::templ
