#include "breastfit/render/torso_overlays.h"

#include <algorithm>
#include <utility>

namespace breastfit::render {

OverlaySizes::OverlaySizes(int size)
    : point_radius_px(std::max(3.0, size / 170.0)), line_width_px(std::max(2.0, size / 340.0)) {}

Rgb drawing_colour(const std::string& name, size_t index) { return to_rgb(mesh::drawing_colour(name, index)); }

ScenePoint landmark_point(const std::string& name, const Vec3& position, const OverlaySizes& sizes) {
  ScenePoint sp;
  sp.label = name;
  sp.position = position;
  sp.colour = kLandmarkColour;
  sp.radius_px = sizes.point_radius_px;
  return sp;
}

void add_placed_landmarks(Scene& scene, const std::vector<NamedPoint>& placed, const std::vector<NamedPoint>& fitted,
                          const OverlaySizes& sizes) {
  if (placed.empty()) return;
  const double width = std::max(1.5, 0.5 * sizes.line_width_px);
  for (const NamedPoint& p : placed) {
    if (!p.position.allFinite()) continue;
    for (const NamedPoint& f : fitted) {
      if (f.name != p.name || !f.position.allFinite()) continue;
      ScenePolyline l;
      l.points.resize(2, 3);
      l.points.row(0) = p.position.transpose();
      l.points.row(1) = f.position.transpose();
      l.colour = kPlacedLandmarkColour;
      l.width_px = width;
      scene.polylines.push_back(std::move(l));
      break;
    }
    ScenePoint sp;
    sp.position = p.position;
    sp.colour = kPlacedLandmarkColour;
    sp.radius_px = 0.7 * sizes.point_radius_px;
    scene.points.push_back(sp);
  }
  ScenePolyline legend_only;  // no points: only a legend entry
  legend_only.name = kPlacedLandmarkLegend;
  legend_only.colour = kPlacedLandmarkColour;
  legend_only.width_px = width;
  scene.polylines.push_back(std::move(legend_only));
}

void add_curve(Scene& scene, const std::string& name, bool closed, const Points& points, const OverlaySizes& sizes) {
  ScenePolyline l;
  l.name = name;
  l.points = points;
  l.closed = closed;
  l.colour = drawing_colour(name, scene.polylines.size());
  l.width_px = sizes.line_width_px;
  scene.polylines.push_back(std::move(l));
}

}  // namespace breastfit::render
