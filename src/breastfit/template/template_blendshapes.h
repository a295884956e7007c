#pragma once
/// \file The template's bounded blendshapes: semantic shapes (per breast: volume, projection,
/// ptosis, shifts, poles, fold height, width, nipple position; global: chest, waist, hips,
/// abdomen, back, shoulders, neck, arms, torso length) and smooth generic modes (symmetric and
/// antisymmetric low-frequency normal fields). Displacements in mm at weight 1.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "breastfit/model/rigged_model.h"
#include "breastfit/template/body_field.h"
#include "breastfit/template/template_mesh.h"

namespace breastfit::templ {

struct BlendshapeOptions {
  int generic_modes = 20;      ///< smooth generic modes (half symmetric, half antisymmetric)
  std::uint64_t seed = 1;      ///< seed of the generic modes
  double generic_amplitude_mm = 4.0;  ///< max displacement of a generic mode at weight 1
  double generic_radius_mm = 70.0;    ///< Gaussian radius of the generic modes' bumps
};

/// How a semantic shape is made.
/// Iso shapes: the rest vertices projected along the surface normal onto the iso-surface of the
/// body with one parameter changed by +/- delta (central difference, so weight 1 = +delta).
/// Explicit shapes: a smooth displacement field (material motion: shifts, sag, stretch).
/// \param weights skin weights of the template (shoulder width and torso length follow them)
/// \param breast_height #V height above the chest wall (masks of the breast shapes)
/// \throws InvalidInput when generic_modes < 0.
std::vector<model::Blendshape> template_blendshapes(const TemplateMesh& tm, const BodyField& field,
                                                    const model::SkinWeights& weights,
                                                    const Eigen::VectorXd& breast_height,
                                                    const BlendshapeOptions& options = {});

/// Displacement (#V by 3) of the rest vertices onto the zero set of `changed` along the rest
/// normals (rest vertices lie on the zero set of `rest`). Vertices whose field value does not
/// change do not move.
Points iso_displacement(const TemplateMesh& tm, const BodyField& rest, const BodyField& changed,
                        const Points& normals);

/// Unit rest normals from the field gradient (tangent to the cut plane on cut boundaries).
Points template_normals(const TemplateMesh& tm, const BodyField& field);

}  // namespace breastfit::templ
