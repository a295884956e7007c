#pragma once
/// \file Small helpers shared by the energy terms to turn point Jacobians into rows.
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/fit/normal_equations.h"
#include "breastfit/model/pose_evaluator.h"

namespace breastfit::fit {

/// Adds the three rows w (d_a + J_a δ)², a = x, y, z, of a point residual d with Jacobian `jac`
/// (`vals` is scratch space, reused between calls).
void add_point_rows(const model::PointJacobian& jac, const Vec3& d, double w, NormalEquations& eq,
                    std::vector<double>& vals);

/// w ‖X(θ) − target‖² for a point X on the posed model's surface; with `eq`, also its three rows
/// (`jac`, `vals`: scratch space). Returns the cost. The landmark terms' residual.
double add_surface_point_residual(const model::PoseEvaluator& ev, const SurfacePoint& point, const Vec3& target,
                                  double w, NormalEquations* eq, model::PointJacobian& jac,
                                  std::vector<double>& vals);

/// Adds the row w (n·d + nᵀJ δ)² of a point-to-plane residual.
void add_plane_row(const model::PointJacobian& jac, const Vec3& d, const Vec3& n, double w, NormalEquations& eq,
                   std::vector<double>& vals);

}  // namespace breastfit::fit
