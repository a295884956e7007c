// The lighting model: colour rounding, the highlight's power, front and back faces.
#include "breastfit/render/detail/shading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace breastfit::render::detail {
namespace {

TEST(Shading, ScaleRgbRoundsAndClamps) {
  EXPECT_EQ(scale_rgb(Vec3(0.49, 0.5, 254.6)), (Rgb{0, 1, 255}));
  EXPECT_EQ(scale_rgb(Vec3(-3, 300, std::numeric_limits<double>::quiet_NaN())), (Rgb{0, 255, 0}));
  EXPECT_EQ(to_vec(Rgb{1, 2, 3}), Vec3(1, 2, 3));
}

TEST(Shading, PowerMatchesPow) {
  for (double x : {0.0, 0.3, 0.77, 1.0})
    for (double e : {0.0, 1.0, 24.0, 64.0, 65.0, 2.5}) EXPECT_NEAR(power(x, e), std::pow(x, e), 1e-14) << x << "^" << e;
}

TEST(Shading, VertexColourOrUniform) {
  Colors C(2, 3);
  C << 10, 20, 30, 40, 50, 60;
  EXPECT_EQ(vertex_colour(C, 1, Vec3(1, 1, 1)), Vec3(40, 50, 60));
  EXPECT_EQ(vertex_colour(Colors(), 1, Vec3(1, 2, 3)), Vec3(1, 2, 3));
}

TEST(Shading, FacingTheLightIsBrighterAndBackFacesAreTinted) {
  Camera camera;  // at +z looking down −z
  const Lighting light = make_lighting(camera);
  EXPECT_NEAR((light.headlight - Vec3(0, 0, 1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(light.key.norm(), 1.0, 1e-12);
  SurfaceStyle style;
  const Vec3 base(200, 200, 200), facing(0, 0, 1), grazing = Vec3(1, 0, 0.2).normalized();
  const Vec3 lit = shade(base, facing, true, light, style), dim = shade(base, grazing, true, light, style);
  EXPECT_GT(lit.sum(), dim.sum());
  // A front face: ambient + headlight + key light, and the highlight.
  const double d2 = std::max(0.0, facing.dot(light.key));
  const double intensity = style.ambient + style.headlight + style.key_light * d2;
  EXPECT_NEAR(lit[0], 200 * intensity + 255 * style.specular, 1e-9);
  // A back face: its base mixed 20 / 80 with back_colour, darkened, no highlight.
  const Vec3 back = shade(base, facing, false, light, style);
  EXPECT_NEAR(back[2], (0.2 * 200 + 0.8 * style.back_colour.b) * intensity * style.back_brightness, 1e-9);
}

}  // namespace
}  // namespace breastfit::render::detail
