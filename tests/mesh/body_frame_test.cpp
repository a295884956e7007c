#include "breastfit/mesh/body_frame.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "breastfit/core/errors.h"
#include "support/test_shapes.h"

namespace breastfit::mesh {
namespace {

/// Landmarks of a schematic torso in the body frame (mm, LPS).
NamedPositions body_landmarks() {
  return {
      {"sternal_notch", Vec3(0, -60, 0)},        {"xiphoid", Vec3(0, -90, -210)},
      {"acromion_R", Vec3(-170, -10, 10)},       {"acromion_L", Vec3(170, -10, 10)},
      {"nipple_R", Vec3(-95, -130, -150)},       {"nipple_L", Vec3(95, -130, -150)},
      {"lowest_breast_R", Vec3(-95, -110, -215)}, {"lowest_breast_L", Vec3(95, -110, -215)},
  };
}

Eigen::Matrix4d test_transform() {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(2.1, Vec3(0.3, -1, 0.5).normalized()).toRotationMatrix();
  T.block<3, 1>(0, 3) = Vec3(-150, 240, 100);
  return T;
}

NamedPositions transformed(const NamedPositions& lm, const Eigen::Matrix4d& T) {
  NamedPositions out;
  for (const auto& [name, p] : lm) out[name] = T.topLeftCorner<3, 3>() * p + T.block<3, 1>(0, 3);
  return out;
}

/// Angle in degrees between corresponding columns.
double axis_error_deg(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b, int col) {
  const double c = a.block<3, 1>(0, col).normalized().dot(b.block<3, 1>(0, col).normalized());
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
}

TEST(BodyFrame, FromLandmarksRecoversTheRotation) {
  const Eigen::Matrix4d T = test_transform();
  // The schematic sternum leans 8.1° (top posterior): corrected with that inclination, the frame
  // is exact; without correction the superior axis follows the sternum.
  const double lean = std::atan2(30.0, 210.0) * 180.0 / 3.14159265358979323846;
  const auto raw = body_frame_from_landmarks(transformed(body_landmarks(), T), 0.0);
  ASSERT_TRUE(raw.has_value());
  EXPECT_NEAR(axis_error_deg(raw->body_to_world, T, 0), 0.0, 1e-6);   // left = acromion_R→L
  EXPECT_NEAR(axis_error_deg(raw->body_to_world, T, 2), lean, 1e-6);  // superior = xiphoid→notch
  EXPECT_NEAR(axis_error_deg(raw->body_to_world, T, 1), lean, 1e-6);
  const auto frame = body_frame_from_landmarks(transformed(body_landmarks(), T), lean);
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->source, BodyFrameSource::Landmarks);
  for (int col = 0; col < 3; ++col) EXPECT_NEAR(axis_error_deg(frame->body_to_world, T, col), 0.0, 1e-6) << col;
  // The default inclination (17°) over-corrects this schematic one by 17 − 8.1°.
  const auto dflt = body_frame_from_landmarks(transformed(body_landmarks(), T));
  EXPECT_NEAR(axis_error_deg(dflt->body_to_world, T, 2), kSternumInclinationDeg - lean, 1e-6);
  EXPECT_THROW(body_frame_from_landmarks(body_landmarks(), 90.0), InvalidInput);
  // Right-handed rotation, origin at the sternal notch.
  const Eigen::Matrix3d R = frame->body_to_world.topLeftCorner<3, 3>();
  EXPECT_NEAR(R.determinant(), 1.0, 1e-9);
  EXPECT_TRUE((R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-9));
  const Vec3 notch = T.topLeftCorner<3, 3>() * Vec3(0, -60, 0) + T.block<3, 1>(0, 3);
  const Vec3 origin = frame->body_to_world.block<3, 1>(0, 3);
  EXPECT_TRUE(origin.isApprox(notch, 1e-9));
  EXPECT_NE(frame->description.find("sternal_notch"), std::string::npos);
}

TEST(BodyFrame, FallsBackToOtherLandmarkPairs) {
  NamedPositions lm = body_landmarks();
  lm.erase("sternal_notch");
  lm.erase("acromion_L");
  lm["acromion_L"] = Vec3(170, -10, 10);  // keep acromions for the vertical
  lm.erase("xiphoid");
  const auto frame = body_frame_from_landmarks(lm);
  ASSERT_TRUE(frame.has_value());
  // Vertical from mid lowest_breast → mid acromion: (0, 100, 225) → mostly +z.
  EXPECT_GT(frame->body_to_world(2, 2), 0.9);
  EXPECT_NEAR(frame->body_to_world(0, 0), 1.0, 1e-9);
  lm.erase("acromion_R");
  lm.erase("acromion_L");
  EXPECT_FALSE(body_frame_from_landmarks(lm).has_value());  // no vertical any more
  EXPECT_FALSE(body_frame_from_landmarks({{"sternal_notch", Vec3(0, 0, 0)}, {"xiphoid", Vec3(0, 0, -200)}}));
}

/// A front-only torso-like scan: the anterior part of an ellipsoid (open at the back), wider at
/// the top (shoulders), mirror-symmetric left/right, in the body frame.
TriangleMesh torso_like() {
  const TriangleMesh sphere = test::sphere_mesh(1.0, Vec3::Zero(), 40, 80);
  TriangleMesh m;
  m.V = sphere.V;
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    const double x = m.V(i, 0), y = m.V(i, 1), z = m.V(i, 2);
    m.V.row(i) << x * (130 + 50 * std::max(z, 0.0)), y * 80, z * 230;
  }
  std::vector<Eigen::Index> keep;
  for (Eigen::Index f = 0; f < sphere.F.rows(); ++f) {
    const double cy = (sphere.V(sphere.F(f, 0), 1) + sphere.V(sphere.F(f, 1), 1) + sphere.V(sphere.F(f, 2), 1)) / 3;
    if (cy < 0.2) keep.push_back(f);
  }
  m.F.resize(static_cast<Eigen::Index>(keep.size()), 3);
  for (size_t k = 0; k < keep.size(); ++k) m.F.row(static_cast<Eigen::Index>(k)) = sphere.F.row(keep[k]);
  return m;
}

TEST(BodyFrame, PrincipalAxesOfATorsoLikeScan) {
  const Eigen::Matrix4d T = test_transform();
  TriangleMesh scan = torso_like();
  for (Eigen::Index i = 0; i < scan.V.rows(); ++i)
    scan.V.row(i) = (T.topLeftCorner<3, 3>() * scan.V.row(i).transpose() + T.block<3, 1>(0, 3)).transpose();
  const BodyFrame frame = body_frame_from_principal_axes(scan);
  EXPECT_EQ(frame.source, BodyFrameSource::PrincipalAxes);
  for (int col = 0; col < 3; ++col) EXPECT_LT(axis_error_deg(frame.body_to_world, T, col), 5.0) << col;
  // Deterministic.
  EXPECT_EQ(body_frame_from_principal_axes(scan).body_to_world, frame.body_to_world);
  // estimate_body_frame prefers landmarks.
  const BodyFrame with_lm = estimate_body_frame(scan, transformed(body_landmarks(), T));
  EXPECT_EQ(with_lm.source, BodyFrameSource::Landmarks);
  const BodyFrame without = estimate_body_frame(scan, {});
  EXPECT_EQ(without.source, BodyFrameSource::PrincipalAxes);
}

TEST(BodyFrame, PrincipalAxesRejectsDegenerateShapes) {
  TriangleMesh tiny;
  tiny.V.resize(3, 3);
  tiny.V.setZero();
  EXPECT_THROW(body_frame_from_principal_axes(tiny), InvalidInput);
  TriangleMesh line;
  line.V.resize(10, 3);
  for (int i = 0; i < 10; ++i) line.V.row(i) << i, 2 * i, 0;
  EXPECT_THROW(body_frame_from_principal_axes(line), InvalidInput);
}

}  // namespace
}  // namespace breastfit::mesh
