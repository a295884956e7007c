#pragma once
/// \file The template's 12 landmarks, surgical drawings (breast contours, inframammary folds,
/// sternum) and vertex regions, placed from the body parameters by their anatomical definitions
/// (docs/TEMPLATE.md, bench README "Landmarks" / "Curves").
#include <vector>

#include <Eigen/Core>

#include "breastfit/model/rigged_model.h"
#include "breastfit/template/body_field.h"
#include "breastfit/template/template_mesh.h"

namespace breastfit::templ {

struct AnnotationOptions {
  double drawing_spacing_mm = 5.0;   ///< spacing of drawing points along their curves
  double footprint_height_mm = 1.5;  ///< breast mound (lowest-point search, breast regions) = where the breast lifts the skin by more than this
  double footprint_margin_mm = 4.0;  ///< breast contour = where the skin lies within this of the breast's ellipsoid (the gland)
  double contour_smoothing_mm = 8.0; ///< Gaussian smoothing of the breast contours along their length
  /// The upper half of the contour is lowered by up to this at its top (∝ the height above the
  /// contour's mid-height): the gland's upper pole thins out into the chest wall, and the
  /// footprint's upper border (2nd–3rd rib) lies below the gland ellipsoid's 4 mm line.
  double contour_top_lowering_mm = 15.0;
  double xiphoid_z = -200.0;         ///< height of the xiphoid tip below the notch (z), mm
};

struct TemplateAnnotations {
  std::vector<model::ModelLandmark> landmarks;  ///< the 12 landmarks in kLandmarkNames order
  std::vector<model::Drawing> drawings;         ///< breast_contour_R/L, imf_R/L, sternum
  std::vector<model::VertexRegion> regions;     ///< breast_R/L and others
};

/// \param breast_height #V height of each vertex above the chest wall (template_skeleton.h)
/// \param weights skin weights (for the anatomical regions)
/// \throws InvalidInput when a landmark or curve cannot be placed (a degenerate body).
TemplateAnnotations template_annotations(const TemplateMesh& tm, const BodyField& field,
                                         const Eigen::VectorXd& breast_height,
                                         const model::SkinWeights& weights,
                                         const AnnotationOptions& options = {});

}  // namespace breastfit::templ
