#include "breastfit/fit/sliding_landmarks.h"

#include <limits>

namespace breastfit::fit {

std::optional<std::string> sliding_landmark_region(const std::string& name) {
  if (name == "lowest_breast_R") return std::string("breast_R");
  if (name == "lowest_breast_L") return std::string("breast_L");
  return std::nullopt;
}

Vec3 posed_vertical_axis(const model::RiggedModel& model, const model::PoseParams& params) {
  Vec3 up = Vec3::UnitZ();
  if (const auto thorax = model.bone_index("thorax")) up = params.bones[*thorax].rotation * up;
  return (params.global.rotation * up).normalized();
}

std::optional<SurfacePoint> lowest_region_point(const model::RiggedModel& model, const Points& V,
                                                const Vec3& vertical, const std::string& region) {
  const auto r = model.region_index(region);
  if (!r || model.regions[*r].vertices.empty()) return std::nullopt;
  Index lowest = model.regions[*r].vertices.front();
  double lowest_height = std::numeric_limits<double>::infinity();
  for (Index v : model.regions[*r].vertices) {
    const double h = vertical.dot(V.row(v).transpose());
    if (h < lowest_height) {
      lowest_height = h;
      lowest = v;
    }
  }
  const Triangles& F = model.rest.F;
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (F(f, c) == lowest) {
        SurfacePoint p;
        p.face = f;
        p.bary = Vec3::Zero();
        p.bary[c] = 1.0;
        return p;
      }
  return std::nullopt;
}

Vec3 model_landmark_position(const model::RiggedModel& model, int landmark, const Points& V,
                             const model::PoseParams& params) {
  const auto& lm = model.landmarks[landmark];
  if (const auto region = sliding_landmark_region(lm.name))
    if (const auto p = lowest_region_point(model, V, posed_vertical_axis(model, params), *region))
      return p->position(V, model.rest.F);
  return lm.point.position(V, model.rest.F);
}

}  // namespace breastfit::fit
