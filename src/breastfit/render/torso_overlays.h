#pragma once
/// \file The standard look of anatomical overlays on a torso image: landmarks as red labelled
/// discs, drawings as coloured polylines (coloured by kind from the one drawing palette,
/// mesh/drawing_palette.h, listed in the legend), sized for the image. Shared by `breastfit render` and the registration report's figures so both
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
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/drawing_palette.h"
#include "breastfit/mesh/landmarks.h"
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

/// A colour of the drawing palette (mesh/drawing_palette.h) as an image colour.
constexpr Rgb to_rgb(const mesh::Rgb8& c) { return {c[0], c[1], c[2]}; }

/// The colour of fitted landmark discs (mesh::kFittedLandmarkColour).
inline constexpr Rgb kLandmarkColour = to_rgb(mesh::kFittedLandmarkColour);
/// The colour of the landmarks a person placed, drawn beside the fitted ones
/// (mesh::kPlacedLandmarkColour).
inline constexpr Rgb kPlacedLandmarkColour = to_rgb(mesh::kPlacedLandmarkColour);

/// The colour of a drawing: mesh::drawing_colour (by kind; others by `index`).
Rgb drawing_colour(const std::string& name, size_t index);

/// A landmark: a red disc labelled with its name.
ScenePoint landmark_point(const std::string& name, const Vec3& position, const OverlaySizes& sizes);

/// The legend entry of add_placed_landmarks.
inline constexpr const char* kPlacedLandmarkLegend = "placed landmark (line to fitted)";

/// Landmarks a person placed, drawn beside the fitted ones: a small dark disc each (no label: the
/// fitted one carries the name), joined by a thin dark line to the fitted landmark of the same
/// name when there is one (the landmark error at a glance), and one legend entry. Nothing when
/// `placed` is empty.
void add_placed_landmarks(Scene& scene, const std::vector<NamedPoint>& placed, const std::vector<NamedPoint>& fitted,
                          const OverlaySizes& sizes);

/// Appends a named drawing in its palette colour (drawing_colour(name, number of polylines so
/// far)), so it appears in the legend.
void add_curve(Scene& scene, const std::string& name, bool closed, const Points& points, const OverlaySizes& sizes);

}  // namespace breastfit::render
