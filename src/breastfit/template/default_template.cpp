#include "breastfit/template/default_template.h"

#include <cstring>

#include "breastfit/core/errors.h"
#include "breastfit/template/body_field.h"
#include "breastfit/template/heat_weights.h"
#include "breastfit/template/template_annotations.h"
#include "breastfit/template/template_blendshapes.h"
#include "breastfit/template/template_mesh.h"
#include "breastfit/template/template_skeleton.h"

namespace breastfit::templ {

void DefaultTemplateOptions::validate() const {
  if (!(target_edge_mm >= 8.0 && target_edge_mm <= 40.0))
    throw InvalidInput("template options: target_edge_mm must be in [8, 40]");
  if (!(grid_step_mm >= 2.0 && grid_step_mm <= 0.75 * target_edge_mm))
    throw InvalidInput("template options: grid_step_mm must be in [2, 0.75 * target_edge_mm]");
  if (generic_modes < 0 || generic_modes > 200) throw InvalidInput("template options: generic_modes must be in [0, 200]");
  if (remesh_iterations < 1 || remesh_iterations > 50)
    throw InvalidInput("template options: remesh_iterations must be in [1, 50]");
  if (!(drawing_spacing_mm >= 1.0 && drawing_spacing_mm <= 20.0))
    throw InvalidInput("template options: drawing_spacing_mm must be in [1, 20]");
  if (!(weight_diffusion_mm2 > 0 && weight_diffusion_mm2 <= 1e5))
    throw InvalidInput("template options: weight_diffusion_mm2 must be in (0, 1e5]");
  static_assert(sizeof(BreastParams) == 16 * sizeof(double), "BreastParams holds doubles only");
  static_assert(sizeof(ArmParams) == 10 * sizeof(double), "ArmParams holds doubles only");
  if (std::memcmp(&body.breast[0], &body.breast[1], sizeof(BreastParams)) != 0 ||
      std::memcmp(&body.arm[0], &body.arm[1], sizeof(ArmParams)) != 0)
    throw InvalidInput("template options: body must be left-right symmetric (breast[0] == breast[1], arm[0] == arm[1])");
}

model::RiggedModel build_default_template(const DefaultTemplateOptions& options) {
  options.validate();
  const BodyField field(options.body);

  TemplateMeshOptions mo;
  mo.target_edge_mm = options.target_edge_mm;
  mo.grid_step_mm = options.grid_step_mm;
  mo.remesh_iterations = options.remesh_iterations;
  const TemplateMesh tm = build_template_mesh(field, mo);

  model::RiggedModel model;
  model.name = "default_torso";
  model.rest = tm.mesh;
  model.bones = template_bones(field);

  const Eigen::VectorXd bh = breast_height(tm.mesh, field);
  HeatWeightOptions wo;
  wo.diffusion_time_mm2 = options.weight_diffusion_mm2;
  model.weights = heat_diffusion_weights(tm.mesh, skin_weight_seeds(tm, field, bh), wo);

  AnnotationOptions ao;
  ao.drawing_spacing_mm = options.drawing_spacing_mm;
  TemplateAnnotations ann = template_annotations(tm, field, bh, model.weights, ao);
  model.landmarks = std::move(ann.landmarks);
  model.drawings = std::move(ann.drawings);
  model.regions = std::move(ann.regions);

  BlendshapeOptions bo;
  bo.generic_modes = options.generic_modes;
  bo.seed = options.seed;
  model.blendshapes = template_blendshapes(tm, field, model.weights, bh, bo);
  return model;
}

}  // namespace breastfit::templ
