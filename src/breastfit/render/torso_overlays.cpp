#include "breastfit/render/torso_overlays.h"

#include <algorithm>
#include <utility>

namespace breastfit::render {

OverlaySizes::OverlaySizes(int size)
    : point_radius_px(std::max(3.0, size / 170.0)), line_width_px(std::max(2.0, size / 340.0)) {}

ScenePoint landmark_point(const std::string& name, const Vec3& position, const OverlaySizes& sizes) {
  ScenePoint sp;
  sp.label = name;
  sp.position = position;
  sp.colour = kLandmarkColour;
  sp.radius_px = sizes.point_radius_px;
  return sp;
}

void add_curve(Scene& scene, const std::string& name, bool closed, const Points& points, const OverlaySizes& sizes) {
  ScenePolyline l;
  l.name = name;
  l.points = points;
  l.closed = closed;
  l.colour = palette_colour(scene.polylines.size());
  l.width_px = sizes.line_width_px;
  scene.polylines.push_back(std::move(l));
}

}  // namespace breastfit::render
