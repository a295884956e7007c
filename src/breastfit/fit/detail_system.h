#pragma once
/// \file The surface detail's sparse system for one mesh topology (fit/surface_detail.h): the
/// matrix μ·L + ε·I of the template's edges (its diagonal set anew per pass) and that matrix's
/// symbolic factorisation (the fill-reducing ordering and the elimination tree: topology only).
///
/// Building them (the edges, the pattern, the ordering) costs about a fifth of a re-fit's surface
/// detail, and the workstation re-fits the same template again and again: a released system is
/// kept (the most recently used few) and leased again to the next fit with the same triangles,
/// vertex count, μ and ε. The numeric factorisation is redone on every use from the symbolic one,
/// so a kept system gives the same bits as a new one. Thread-safe: a system is leased to one fit
/// at a time (two fits at once of the same template get one each).
#include <memory>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "breastfit/core/types.h"

namespace breastfit::fit {

struct DetailSystem {
  /// \param F the triangles (indices < n); \param smoothness μ; \param decay ε (> 0 for SPD)
  DetailSystem(const Triangles& F, Index n, double smoothness, double decay);

  Triangles F;                ///< the key: triangles, vertex count, μ, ε
  Index n = 0;
  double smoothness = 0, decay = 0;
  Eigen::SparseMatrix<double> A;                           ///< −μ per edge, the diagonal's entries present (values: the caller's)
  Eigen::VectorXd base_diag;                               ///< ε + μ · (edges at the vertex)
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;  ///< analyzePattern(A) done

  bool matches(const Triangles& f, Index num_vertices, double mu, double eps) const;
};

/// A system for (F, n, μ, ε) for the caller's exclusive use: a kept one when a released one
/// matches, else a new one. Released (and kept) when the last copy of the pointer goes.
std::shared_ptr<DetailSystem> lease_detail_system(const Triangles& F, Index n, double smoothness, double decay);

}  // namespace breastfit::fit
