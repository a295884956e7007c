#pragma once
/// \file The standard look of anatomical overlays on a torso image: landmarks as red labelled
/// discs, drawings as coloured polylines (one palette colour each, listed in the legend), sized
/// for the image. Shared by `breastfit render` and the registration report's figures so both
/// show a fit the same way.
///
/// Example:
/// \code
///   const render::OverlaySizes sizes(900);
///   render::Scene scene;
///   scene.points.push_back(render::landmark_point("nipple_R", p, sizes));
///   render::add_curve(scene, "breast_contour_R", true, P, sizes);
/// \endcode
#include <string>

#include "breastfit/core/types.h"
#include "breastfit/render/scene.h"

namespace breastfit::render {

/// Overlay sizes for a square image of `size` pixels: 6 px discs and 3 px lines at 1024 px,
/// never smaller than 3 px discs and 2 px lines.
struct OverlaySizes {
  double point_radius_px = 6.0;
  double line_width_px = 3.0;
  OverlaySizes() = default;
  explicit OverlaySizes(int size);
};

/// The colour of landmark discs (a saturated red that stands out on skin and on the colour maps).
inline constexpr Rgb kLandmarkColour = {215, 25, 32};

/// A landmark: a red disc labelled with its name.
ScenePoint landmark_point(const std::string& name, const Vec3& position, const OverlaySizes& sizes);

/// Appends a named drawing in the next palette colour (palette_colour(number of polylines so
/// far)), so it appears in the legend.
void add_curve(Scene& scene, const std::string& name, bool closed, const Points& points, const OverlaySizes& sizes);

}  // namespace breastfit::render
