#pragma once
/// \file Surface detail: a smooth per-vertex offset along the posed model's normals, fitted to the
/// scan after the parametric registration (beyond the paper; docs/REGISTRATION.md "Surface detail").
///
/// The template's parameters (bones, blendshapes) explain the body's shape only as far as the
/// template's shape space reaches; what is left — a flatter flank, a rounder belly, a deltoid — is
/// a few mm of smooth normal displacement. The detail layer fits it by a sparse linear least-squares
/// problem per pass:
///   min_h  Σ_{i∈C} w_i (h_i − r_i)²  +  μ Σ_{(i,j)∈E} (h_i − h_j)²  +  ε Σ_i h_i²
/// r_i: distance along the model normal n_i from vertex i to the scan's tangent plane at its
/// closest point (same rejection as the data term: open border, distance, normals); w_i: robust
/// weight of the residual left by the previous pass; E: the template's edges. Vertices without a
/// correspondence (holes, the back) are filled in smoothly from their neighbours and fade to 0.
/// Offsets move vertices only along the normal, so material points (landmarks, drawings) keep
/// their place on the body; |h| is clamped to max_offset_mm.
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/fit/correspondences.h"
#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/scan_target.h"

namespace breastfit::fit {

struct SurfaceDetail {
  Eigen::VectorXd offsets;  ///< per vertex, mm along the posed model's unit vertex normal
  Points vertices;          ///< posed vertices + offsets · normals
  int kept = 0;             ///< correspondences used in the last pass
  double mean_abs_mm = 0, max_abs_mm = 0;
};

/// The first pass's correspondences when the caller has them already: those of every vertex of V
/// (stride 1) with the normals vertex_normals(V, F) at options.max_distance_mm — e.g. the fit's
/// final pairs when its end threshold is the detail's (fit/registration.cpp). `hints`: the
/// searches' warm starts per vertex (only the speed depends on them; may be empty).
struct DetailFirstPass {
  const std::vector<Correspondence>& pairs;
  const std::vector<Index>& hints;
};

/// Fits the offsets for the posed vertices V (faces F) to the scan. `threads`: for the
/// correspondence searches (≤ 0: all cores); the result does not depend on it. With `first`, the
/// first pass uses its pairs instead of searching (the same result, one search less).
SurfaceDetail fit_surface_detail(const Points& V, const Triangles& F, const ScanTarget& scan,
                                 const CorrespondenceOptions& correspondences, const SurfaceDetailOptions& options,
                                 int threads = 0, const DetailFirstPass* first = nullptr);

/// V + offsets · vertex_normals(V, F). \throws InvalidInput when sizes differ.
Points apply_surface_detail(const Points& V, const Triangles& F, const Eigen::VectorXd& offsets);

}  // namespace breastfit::fit
