#pragma once
/// \file Smooth skin weights by heat diffusion on the mesh: (M - t L) w = M s per bone, with the
/// cotangent Laplacian L and the lumped (barycentric) mass matrix M, then pruning and
/// renormalisation.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::templ {

struct HeatWeightOptions {
  double diffusion_time_mm2 = 500.0;  ///< t; the blur radius is about sqrt(4 t) mm
  int max_influences = 4;             ///< bones kept per vertex (largest weights)
  double prune_below = 0.01;          ///< weights below this are dropped before renormalising
};

/// Cotangent Laplacian (#V by #V, negative semi-definite, cotangents clamped to [-5, 5]).
Eigen::SparseMatrix<double> cotan_laplacian(const TriangleMesh& mesh);
/// Lumped barycentric mass matrix diagonal (#V; mm^2).
Eigen::VectorXd vertex_areas(const TriangleMesh& mesh);

/// Diffuses each column of `seeds` (#V by #bones, >= 0, rows not all zero) and returns
/// non-negative weights with at most max_influences per row, each row summing to 1.
/// \throws InvalidInput on size mismatch or a bad option.
model::SkinWeights heat_diffusion_weights(const TriangleMesh& mesh, const Eigen::MatrixXd& seeds,
                                          const HeatWeightOptions& options = {});

/// Smooths per-vertex values (#V by k) by the same implicit diffusion (no pruning).
Eigen::MatrixXd diffuse(const TriangleMesh& mesh, const Eigen::MatrixXd& values, double time_mm2);

}  // namespace breastfit::templ
