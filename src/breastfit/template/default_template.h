#pragma once
/// \file Front door of the template layer: the default rigged template, a plausible adult female
/// upper torso (umbilicus to neck base, upper arms to mid-humerus, open at the cuts), generated
/// from a parametric implicit body (docs/TEMPLATE.md). Millimetres, body frame LPS (x = patient
/// left, y = posterior, z = superior), origin at the sternal notch.
#include <cstdint>

#include "breastfit/model/rigged_model.h"
#include "breastfit/template/body_params.h"

namespace breastfit::templ {

struct DefaultTemplateOptions {
  double target_edge_mm = 16.0;       ///< remeshing edge length; 16 mm gives ~2000-3000 vertices
  std::uint64_t seed = 1;             ///< seed of the generic blendshape modes
  int generic_modes = 20;             ///< smooth generic blendshapes added after the semantic ones
  double grid_step_mm = 7.0;          ///< marching-tetrahedra grid step (<= 0.75 target_edge_mm)
  int remesh_iterations = 10;         ///< isotropic remeshing rounds
  double drawing_spacing_mm = 5.0;    ///< spacing of the drawing points
  double weight_diffusion_mm2 = 250;  ///< heat-diffusion time of the skin weights (blur ~ sqrt(4t) ~ 32 mm)
  BodyParams body{};                  ///< the anatomy; must be left-right symmetric

  /// \throws InvalidInput naming the bad field.
  void validate() const;
};

/// Builds the default template. Deterministic: the same options give a bit-identical model.
/// Single-threaded; about a second.
/// \throws InvalidInput for invalid options.
model::RiggedModel build_default_template(const DefaultTemplateOptions& options = {});

}  // namespace breastfit::templ
