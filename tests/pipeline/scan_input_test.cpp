#include "breastfit/pipeline/scan_input.h"

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"
#include "breastfit/core/rng.h"

namespace breastfit::pipeline {
namespace {

// An open half-cylinder "torso front" of radius r (file units), height h.
TriangleMesh half_cylinder(double r, double h, int nu = 40, int nv = 30) {
  TriangleMesh m;
  m.V.resize(nu * nv, 3);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double a = M_PI * i / (nu - 1);
      m.V.row(j * nu + i) << r * std::cos(a), -r * std::sin(a), h * j / (nv - 1);
    }
  m.F.resize(2 * (nu - 1) * (nv - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < nv; ++j)
    for (int i = 0; i + 1 < nu; ++i) {
      const int a = j * nu + i, b = a + 1, c = a + nu, d = c + 1;
      m.F.row(f++) << a, c, b;
      m.F.row(f++) << b, c, d;
    }
  return m;
}

TEST(ScanInput, DetectsMetresAndConvertsToMillimetres) {
  const auto scan = half_cylinder(0.15, 0.45);
  const auto p = prepare_scan(scan, "scan.ply", std::nullopt);
  EXPECT_EQ(p.units, mesh::Units::Metres);
  EXPECT_DOUBLE_EQ(p.to_mm, 1000.0);
  EXPECT_NEAR(p.mesh_mm.V.col(2).maxCoeff(), 450.0, 1e-9);
}

TEST(ScanInput, ForcedUnitsWin) {
  const auto scan = half_cylinder(150, 450);
  EXPECT_EQ(prepare_scan(scan, "scan.ply", mesh::Units::Millimetres).units, mesh::Units::Millimetres);
  // 450 m is no torso
  EXPECT_THROW(prepare_scan(scan, "scan.ply", mesh::Units::Metres), InvalidInput);
}

TEST(ScanInput, RejectsScansThatAreNotATorso) {
  const auto tiny = half_cylinder(20, 40);  // 40 mm
  try {
    prepare_scan(tiny, "tiny.ply", mesh::Units::Millimetres);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("tiny.ply"), std::string::npos);
  }
  auto nan = half_cylinder(150, 450);
  nan.V(3, 1) = NAN;
  EXPECT_THROW(prepare_scan(nan, "nan.ply", std::nullopt), InvalidInput);
  EXPECT_THROW(prepare_scan(TriangleMesh{}, "empty.ply", std::nullopt), InvalidInput);
}

TEST(ScanInput, WarnsAboutASizeFarFromAnAdultTorso) {
  // A 0.155 m bunny taken as 155 mm: kept, but said.
  const auto small = prepare_scan(half_cylinder(50, 155), "bunny.ply", std::nullopt);
  ASSERT_EQ(small.warnings.size(), 1u);
  EXPECT_NE(small.warnings[0].find("bunny.ply: the scan spans 155 mm (in mm), small for an adult upper torso"),
            std::string::npos)
      << small.warnings[0];
  EXPECT_TRUE(prepare_scan(half_cylinder(150, 450), "torso.ply", std::nullopt).warnings.empty());
  const auto large = prepare_scan(half_cylinder(300, 1200), "body.ply", mesh::Units::Millimetres);
  ASSERT_EQ(large.warnings.size(), 1u);
  EXPECT_NE(large.warnings[0].find("large for an adult upper torso"), std::string::npos);
}

TEST(ScanInput, PointCloudsBecomeOrientedSplats) {
  auto scan = half_cylinder(150, 450);
  scan.F.resize(0, 3);
  const auto p = prepare_scan(scan, "cloud.ply", std::nullopt);
  EXPECT_TRUE(p.was_point_cloud);
  EXPECT_EQ(p.mesh_mm.num_faces(), scan.num_vertices());
  EXPECT_FALSE(p.warnings.empty());
}

}  // namespace
}  // namespace breastfit::pipeline
