#pragma once
/// \file The template surface: the left half of the implicit body meshed (marching tetrahedra,
/// clipping at the cuts and the mid-sagittal plane, isotropic remeshing) and mirrored, so that
/// the mesh is exactly left-right symmetric with its seam on x = 0.
#include <cstdint>
#include <vector>

#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/template/body_field.h"

namespace breastfit::templ {

/// Cut indices of TemplateMesh::on_cut bits (1 << kCut...).
inline constexpr int kCutWaist = 0, kCutNeck = 1, kCutArmR = 2, kCutArmL = 3;

struct TemplateMesh {
  TriangleMesh mesh;                  ///< symmetric, open at the 4 cuts, CCW = outward
  std::vector<std::uint32_t> on_cut;  ///< #V bit masks of the cuts a boundary vertex lies on
  std::vector<Index> mirror;          ///< #V: index of the mirror image vertex (itself on x = 0)
  std::vector<CutPlane> cuts;         ///< waist, neck, arm_R, arm_L
};

struct TemplateMeshOptions {
  double target_edge_mm = 16.0;  ///< isotropic remeshing target edge length
  double grid_step_mm = 7.0;     ///< marching-tetrahedra grid step
  int remesh_iterations = 10;    ///< remeshing rounds
};

/// Meshes the body (which must be left-right symmetric). Deterministic.
/// \throws InvalidInput on bad options.
TemplateMesh build_template_mesh(const BodyField& field, const TemplateMeshOptions& options = {});

}  // namespace breastfit::templ
