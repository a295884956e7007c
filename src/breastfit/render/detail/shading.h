#pragma once
/// \file The rasterizer's lighting model (private to the render layer): a headlight, a key light
/// from the viewer's upper left and a Blinn-Phong highlight, per SurfaceStyle. Inline: it runs
/// once per lit pixel or sample.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "breastfit/core/types.h"
#include "breastfit/render/camera.h"
#include "breastfit/render/image.h"
#include "breastfit/render/rasterizer.h"

namespace breastfit::render::detail {

inline Rgb scale_rgb(const Vec3& c) {
  // Round half up after clamping to [0, 255] (NaN → 0): no libm call per channel.
  auto ch = [](double v) { return static_cast<std::uint8_t>(v > 0 ? std::min(v, 255.0) + 0.5 : 0.0); };
  return {ch(c[0]), ch(c[1]), ch(c[2])};
}

inline Vec3 to_vec(Rgb c) { return Vec3(c.r, c.g, c.b); }

/// Vertex i's base colour: its row of C, or `uniform` when C is empty.
inline Vec3 vertex_colour(const Colors& C, Index i, const Vec3& uniform) {
  return C.rows() ? Vec3(C(i, 0), C(i, 1), C(i, 2)) : uniform;
}

/// Lights and viewing direction in world coordinates.
struct Lighting {
  Vec3 headlight;  // towards the camera
  Vec3 key;        // towards the key light (upper left of the viewer)
};

inline Lighting make_lighting(const Camera& cam) {
  const Vec3 f = cam.forward(), r = cam.right(), u = cam.true_up();
  return {-f, (-0.8 * f + 0.7 * u - 0.5 * r).normalized()};
}

/// x^e for x in [0, 1]: by repeated squaring when e is a whole number up to 64 (the default
/// shininess 24: five multiplications instead of a pow call per pixel), else std::pow.
inline double power(double x, double e) {
  const int n = static_cast<int>(e);
  if (n != e || n < 0 || n > 64) return std::pow(x, e);
  double result = 1.0, base = x;
  for (int k = n; k > 0; k >>= 1) {
    if (k & 1) result *= base;
    base *= base;
  }
  return result;
}

/// Shaded colour of a surface sample whose normal `n` already faces the viewer.
inline Vec3 shade(const Vec3& base, const Vec3& n, bool front, const Lighting& light, const SurfaceStyle& s) {
  const double d1 = std::max(0.0, n.dot(light.headlight));
  const double d2 = std::max(0.0, n.dot(light.key));
  const double intensity = s.ambient + s.headlight * d1 + s.key_light * d2;
  if (!front) {
    const Vec3 tinted = 0.2 * base + 0.8 * to_vec(s.back_colour);
    return tinted * (intensity * s.back_brightness);
  }
  const double spec = s.specular > 0 ? s.specular * power(d1, s.shininess) : 0.0;
  return base * intensity + Vec3::Constant(255.0 * spec);
}

}  // namespace breastfit::render::detail
