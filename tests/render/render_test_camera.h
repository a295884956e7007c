#pragma once
// The render tests' camera (header-only, test code).
#include "breastfit/render/camera.h"

namespace breastfit::test {

/// Orthographic camera at −y looking +y (a front view: image right = +x, image up = +z),
/// showing `view_height` units.
inline render::Camera front_camera(double view_height) {
  render::Camera c;
  c.eye = Vec3(0, -50, 0);
  c.target = Vec3::Zero();
  c.up = Vec3(0, 0, 1);
  c.view_height = view_height;
  return c;
}

}  // namespace breastfit::test
