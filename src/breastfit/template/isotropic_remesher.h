#pragma once
/// \file Isotropic remeshing (Botsch & Kobbelt 2004: split, collapse, flip, tangential
/// smoothing) of a clipped iso-surface, projecting every vertex back onto the implicit body and
/// keeping cut-boundary vertices exactly on their cut planes.
#include <vector>

#include "breastfit/template/body_field.h"
#include "breastfit/template/plane_clip.h"

namespace breastfit::templ {

struct RemeshOptions {
  double target_edge_mm = 16.0;  ///< target edge length L (splits above 4/3 L, collapses below 4/5 L)
  int iterations = 10;           ///< split/collapse/flip/smooth rounds
  int smoothing_steps = 2;       ///< tangential smoothing sweeps per round
};

/// Remeshes `input` (whose vertices lie near the zero set of `field`; on_cut bit c marks vertices
/// on cuts[c]). Vertices on two cuts (corners) stay fixed; vertices on one cut slide along the
/// cut curve; all others slide on the surface. Deterministic.
/// \throws InvalidInput when target_edge_mm <= 0 or iterations < 0.
ClippedMesh isotropic_remesh(const ClippedMesh& input, const BodyField& field,
                             const std::vector<CutPlane>& cuts, const RemeshOptions& options = {});

}  // namespace breastfit::templ
