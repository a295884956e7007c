#include "breastfit/transfer/curve_region.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

#include "breastfit/core/errors.h"
#include "support/grid_mesh.h"

namespace breastfit::transfer {
namespace {

/// A closed circle of n points, centre c, radius r, in the plane spanned by unit u, v.
Points circle(const Vec3& c, double r, int n, const Vec3& u = Vec3::UnitX(), const Vec3& v = Vec3::UnitY(),
              const std::function<double(double, double)>& z = {}) {
  Points P(n, 3);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    Vec3 p = c + r * (std::cos(t) * u + std::sin(t) * v);
    if (z) p.z() = z(p.x(), p.y());
    P.row(i) = p.transpose();
  }
  return P;
}

/// Indices of the vertices satisfying pred, asserting none is within `tie` of the boundary.
std::vector<Index> where(const TriangleMesh& m, const std::function<double(const Vec3&)>& signed_inside) {
  std::vector<Index> out;
  for (Index v = 0; v < m.num_vertices(); ++v)
    if (signed_inside(m.V.row(v).transpose()) > 0) out.push_back(v);
  return out;
}

/// Rows of the mesh farther than `tie` from the boundary where the two sets disagree.
int disagreements(const TriangleMesh& m, const std::vector<Index>& got, const std::function<double(const Vec3&)>& signed_inside,
                  double tie) {
  std::vector<char> in(static_cast<size_t>(m.num_vertices()), 0);
  for (Index v : got) in[static_cast<size_t>(v)] = 1;
  int bad = 0;
  for (Index v = 0; v < m.num_vertices(); ++v) {
    const double s = signed_inside(m.V.row(v).transpose());
    if (std::abs(s) < tie) continue;
    if ((s > 0) != static_cast<bool>(in[static_cast<size_t>(v)])) ++bad;
  }
  return bad;
}

TEST(CurveRegion, CircleOnAGridSelectsExactlyTheVerticesInside) {
  const double A = 20, sigma = 12;
  auto bump = [&](double x, double y) { return A * std::exp(-(x * x + y * y) / (2 * sigma * sigma)); };
  const TriangleMesh g = test::grid_mesh(60, 1.0, bump);
  const Vec3 c(3.3, -2.7, 0);
  const double r = 25.7;
  const Points curve = circle(c, r, 500, Vec3::UnitX(), Vec3::UnitY(), bump);
  const std::vector<Index> got = vertices_inside_curve(g, curve);
  auto inside = [&](const Vec3& p) { return r - (p - c).head<2>().norm(); };
  const std::vector<Index> expected = where(g, inside);
  ASSERT_GT(expected.size(), 1500u);
  // Chords of the 500-gon lie within r (1 − cos(π/500)) ≈ 0.5 µm of the circle.
  EXPECT_EQ(disagreements(g, got, inside, 1e-3), 0);
  EXPECT_NEAR(static_cast<double>(got.size()), static_cast<double>(expected.size()), 2.0);
  EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
  EXPECT_EQ(std::adjacent_find(got.begin(), got.end()), got.end());

  // Same region whatever the start point, direction, a repeated closing point, or a rigid motion.
  Points reversed = curve.colwise().reverse();
  EXPECT_EQ(vertices_inside_curve(g, reversed), got);
  Points shifted(curve.rows() + 1, 3);
  for (Eigen::Index i = 0; i < curve.rows(); ++i) shifted.row(i) = curve.row((i + 137) % curve.rows());
  shifted.row(curve.rows()) = shifted.row(0);
  EXPECT_EQ(vertices_inside_curve(g, shifted), got);
  const Eigen::AngleAxisd R(1.1, Vec3(0.2, -0.7, 0.4).normalized());
  const Vec3 t(120, -35, 800);
  TriangleMesh moved = g;
  moved.V = ((g.V * R.toRotationMatrix().transpose()).rowwise() + t.transpose()).eval();
  const Points moved_curve = ((curve * R.toRotationMatrix().transpose()).rowwise() + t.transpose()).eval();
  EXPECT_EQ(vertices_inside_curve(moved, moved_curve), got);
}

TEST(CurveRegion, CurveAFewMillimetresOffTheSurface) {
  const TriangleMesh g = test::grid_mesh(40, 1.5);
  const Vec3 c(1.1, 0.4, 0);
  const double r = 30.2;
  const Points on = circle(c, r, 400);
  Points off = on;
  off.col(2).array() += 3.0;  // 3 mm above the surface
  const auto inside = [&](const Vec3& p) { return r - (p - c).head<2>().norm(); };
  EXPECT_EQ(disagreements(g, vertices_inside_curve(g, off), inside, 1e-3), 0);
  EXPECT_EQ(vertices_inside_curve(g, off), vertices_inside_curve(g, on));
}

TEST(CurveRegion, IgnoresAFloatingFragmentUnderTheCurve) {
  // A scan fragment (a 4 x 4 mm patch) floating right on the curve, 3 mm above the surface:
  // the curve's samples there snap onto it, but it is not part of the surface the curve cuts.
  const TriangleMesh g = test::grid_mesh(40, 1.5);
  const Vec3 c(1.1, 0.4, 0);
  const double r = 30.2;
  Points curve = circle(c, r, 400);
  curve.col(2).array() += 3.0;
  TriangleMesh with = g;
  TriangleMesh frag = test::grid_mesh(2, 1.0);
  frag.V.rowwise() += curve.row(0);
  with.V.conservativeResize(g.V.rows() + frag.V.rows(), 3);
  with.V.bottomRows(frag.V.rows()) = frag.V;
  with.F.conservativeResize(g.F.rows() + frag.F.rows(), 3);
  with.F.bottomRows(frag.F.rows()) = frag.F.array() + g.num_vertices();
  EXPECT_EQ(vertices_inside_curve(with, curve), vertices_inside_curve(g, curve));
  EXPECT_NEAR(volume_inside_curve_ml(with, curve), volume_inside_curve_ml(g, curve), 1e-9);
}

/// UV sphere (outward triangles) of radius R around the origin.
TriangleMesh sphere(double R, int nlat, int nlon) {
  TriangleMesh m;
  m.V.resize(2 + (nlat - 1) * nlon, 3);
  m.V.row(0) << 0, 0, R;
  m.V.row(1) << 0, 0, -R;
  for (int i = 1; i < nlat; ++i)
    for (int j = 0; j < nlon; ++j) {
      const double th = M_PI * i / nlat, ph = 2 * M_PI * j / nlon;
      m.V.row(2 + (i - 1) * nlon + j) << R * std::sin(th) * std::cos(ph), R * std::sin(th) * std::sin(ph), R * std::cos(th);
    }
  auto at = [&](int i, int j) { return 2 + (i - 1) * nlon + (j % nlon); };
  std::vector<Eigen::Vector3i> f;
  for (int j = 0; j < nlon; ++j) {
    f.emplace_back(0, at(1, j), at(1, j + 1));
    f.emplace_back(1, at(nlat - 1, j + 1), at(nlat - 1, j));
    for (int i = 1; i + 1 < nlat; ++i) {
      f.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      f.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  m.F.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (size_t k = 0; k < f.size(); ++k) m.F.row(static_cast<Eigen::Index>(k)) = f[k].transpose();
  return m;
}

TEST(CurveRegion, ClosedBodyKeepsTheFrontSheetOnly) {
  const double R = 100;
  const TriangleMesh s = sphere(R, 90, 180);
  const Vec3 axis = Vec3(0.3, -0.8, 0.5).normalized();
  const Vec3 u = axis.unitOrthogonal(), v = axis.cross(u);
  const double cone = 40 * M_PI / 180;
  const Points curve = circle(R * std::cos(cone) * axis, R * std::sin(cone), 600, u, v);
  const std::vector<Index> got = vertices_inside_curve(s, curve);
  const auto inside = [&](const Vec3& p) { return R * (p.normalized().dot(axis) - std::cos(cone)); };
  EXPECT_EQ(disagreements(s, got, inside, 0.01), 0);
  // the back of the sphere projects inside the circle but must not be selected
  for (Index i : got) EXPECT_GT(s.V.row(i).dot(axis), 0.0) << i;
  const std::vector<Index> expected = where(s, inside);
  EXPECT_NEAR(static_cast<double>(got.size()), static_cast<double>(expected.size()), 2.0);

  // A wide cone (a steep flank seen from the curve's plane) drawn 8 mm off the surface (a curve
  // drawn on a scan, measured on a fit): the same region as the curve on the surface. Seen in the
  // curve's plane the drawn curve is ~7 mm outside the surface's border, two edges: vertices
  // outside the border would project inside the drawn curve.
  const double wide = 60 * M_PI / 180;
  const Points on = circle(R * std::cos(wide) * axis, R * std::sin(wide), 600, u, v);
  const Points off = on * (R + 8) / R;
  const auto inside_wide = [&](const Vec3& p) { return R * (p.normalized().dot(axis) - std::cos(wide)); };
  const CurveRegion r_off = curve_region(s, off);
  EXPECT_NEAR(r_off.mean_curve_distance_mm, 8.0, 0.1);
  // (its feet lie on the sphere's flat triangles, up to 0.02 mm inside the sphere: ties within 0.1 mm)
  EXPECT_EQ(disagreements(s, r_off.inside, inside_wide, 0.1), 0);
  EXPECT_EQ(disagreements(s, vertices_inside_curve(s, on), inside_wide, 0.01), 0);
  EXPECT_NEAR(static_cast<double>(r_off.inside.size()), static_cast<double>(where(s, inside_wide).size()), 3.0);
}

TEST(CurveRegion, OverhangingBumpIsKeptAndItsVolumeIsExact) {
  // A spherical cap sheared sideways: its top hangs 1.2 h beyond the base circle (like a ptotic
  // breast over its fold) so it projects partly outside the curve; it must still all be inside.
  // A shear keeps volumes and the base plane, so the volume is the cap's.
  const double Rs = 50, a = 30;
  const double h = Rs - std::sqrt(Rs * Rs - a * a);
  const double k = 1.2 * a / h;  // top displaced by 1.2 a in −x
  TriangleMesh g = test::grid_mesh(60, 1.0);
  const Vec3 c(0.35, 0.45, 0);
  std::vector<char> in_cap(static_cast<size_t>(g.num_vertices()), 0);
  std::vector<double> r0(static_cast<size_t>(g.num_vertices()));
  for (Index v = 0; v < g.num_vertices(); ++v) {
    const double r = (g.V.row(v).transpose() - c).head<2>().norm();
    r0[static_cast<size_t>(v)] = r;
    if (r < a) {
      const double z = std::sqrt(Rs * Rs - r * r) - (Rs - h);
      g.V(v, 2) = z;
      g.V(v, 0) -= k * z;
      in_cap[static_cast<size_t>(v)] = 1;
    }
  }
  const Points curve = circle(c, a, 500);
  const CurveRegion region = curve_region(g, curve);
  int outside_projection = 0;
  for (Index v = 0; v < g.num_vertices(); ++v)
    if (in_cap[static_cast<size_t>(v)] && (g.V.row(v).transpose() - c).head<2>().norm() > a) ++outside_projection;
  ASSERT_GT(outside_projection, 100);  // the overhang is real
  // Exact away from the rim; within 0.5 mm of the base circle the sheared rim triangles fold
  // over the plane (a vertex 0.1 mm inside is moved 0.3 mm outside): either answer is right.
  int bad = 0, near_rim = 0;
  for (Index v = 0; v < g.num_vertices(); ++v) {
    const bool got = std::binary_search(region.inside.begin(), region.inside.end(), v);
    if (got == static_cast<bool>(in_cap[static_cast<size_t>(v)])) continue;
    (std::abs(r0[static_cast<size_t>(v)] - a) < 0.5 ? near_rim : bad)++;
  }
  EXPECT_EQ(bad, 0);
  EXPECT_LT(near_rim, 10);
  EXPECT_LT(region.mean_curve_distance_mm, 0.5);  // the sheared rim triangles are not flat
  const double exact = M_PI * h * h * (3 * Rs - h) / 3.0;
  const CurveVolume vol = curve_volume(g, curve);
  EXPECT_NEAR(vol.volume_ml * 1000, exact, 0.02 * exact);
  EXPECT_EQ(vol.region, region.inside);
}

TEST(CurveRegion, GaussianBumpVolumeOnACoarseMeshAfterRefinement) {
  // Bump cut by a circle at r = a: the membrane is the plane z = f(a).
  const double A = 20, sigma = 15, a = 35;
  auto f = [&](double x, double y) { return A * std::exp(-(x * x + y * y) / (2 * sigma * sigma)); };
  const double e = std::exp(-a * a / (2 * sigma * sigma));
  const double exact = 2 * M_PI * A * sigma * sigma * (1 - e) - M_PI * a * a * A * e;
  const Points curve = circle(Vec3(0.2, -0.3, 0), a, 500, Vec3::UnitX(), Vec3::UnitY(), f);
  for (double step : {1.0, 5.0}) {
    const TriangleMesh g = test::grid_mesh(static_cast<int>(std::lround(70 / step)), step, f);
    const CurveVolume fine = curve_volume(g, curve);  // default: refined to 2 mm edges
    CurveVolumeOptions raw;
    raw.target_edge_mm = 0;
    const CurveVolume coarse = curve_volume(g, curve, raw);
    std::printf("grid %.0f mm: %.0f mm3 refined (%d levels), %.0f mm3 as given, %.0f mm3 exact\n", step,
                fine.volume_ml * 1000, fine.refinement_levels, coarse.volume_ml * 1000, exact);
    EXPECT_NEAR(fine.volume_ml * 1000, exact, (step > 2 ? 0.03 : 0.005) * exact) << step;
    EXPECT_NEAR(coarse.volume_ml * 1000, exact, 0.03 * exact) << step;
    EXPECT_EQ(fine.refinement_levels, step > 2 ? 2 : 0);
    // The rule "vertices inside the curve, fill pinned on the first vertices outside" measures a
    // band up to an edge wide around the curve too: farther from the exact volume.
    const double outside_pins = region_volume(g, vertices_inside_curve(g, curve)).volume_mm3;
    std::printf("  pinned on the first outside vertices: %.0f mm3\n", outside_pins);
    EXPECT_GT(outside_pins - exact, std::abs(fine.volume_ml * 1000 - exact)) << step;
  }
  // A bump on a gently curved (cylindrical, R = 300 mm) chest, thin plate vs membrane both
  // positive and the membrane larger (it sags under the convex wall).
  const double Rc = 300;
  auto chest = [&](double x, double y) { return std::sqrt(Rc * Rc - x * x) - Rc + f(x, y); };
  const TriangleMesh g = test::grid_mesh(35, 2.0, chest);
  const Points on_chest = circle(Vec3(0, 0, 0), a, 400, Vec3::UnitX(), Vec3::UnitY(), chest);
  CurveVolumeOptions tp;
  tp.volume.fill = ChestWallFill::ThinPlate;
  const double vm = volume_inside_curve_ml(g, on_chest), vt = volume_inside_curve_ml(g, on_chest, tp);
  EXPECT_GT(vt, 0);
  EXPECT_GT(vm, vt);
  EXPECT_LT(vm, 1.5 * exact / 1000);
}

// The grid without its triangles that touch the disc of radius r around (x, y).
TriangleMesh with_hole(const TriangleMesh& g, double x, double y, double r) {
  TriangleMesh out = g;
  std::vector<Index> keep;
  for (Index f = 0; f < g.num_faces(); ++f) {
    bool near = false;
    for (int k = 0; k < 3; ++k) near = near || (g.V.row(g.F(f, k)).head<2>() - Eigen::RowVector2d(x, y)).norm() < r;
    if (!near) keep.push_back(f);
  }
  out.F.resize(static_cast<Index>(keep.size()), 3);
  for (size_t i = 0; i < keep.size(); ++i) out.F.row(static_cast<Index>(i)) = g.F.row(keep[i]);
  return out;
}

TEST(CurveRegion, AHoleInsideTheCurveIsRefusedOneOutsideIsNot) {
  const double A = 20, sigma = 15, a = 35;
  auto f = [&](double x, double y) { return A * std::exp(-(x * x + y * y) / (2 * sigma * sigma)); };
  const TriangleMesh g = test::grid_mesh(35, 2.0, f);
  const Points curve = circle(Vec3(0, 0, 0), a, 400, Vec3::UnitX(), Vec3::UnitY(), f);
  const double closed = volume_inside_curve_ml(g, curve);
  // A hole on the bump's flank, inside the curve: measured, the volume would be wrong.
  try {
    (void)volume_inside_curve_ml(with_hole(g, 12, 5, 7), curve);
    ADD_FAILURE() << "a hole inside the curve was measured";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("1 hole or open border"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fitted.ply"), std::string::npos) << e.what();
  }
  // A hole well outside the curve changes nothing.
  EXPECT_NEAR(volume_inside_curve_ml(with_hole(g, 55, 50, 6), curve), closed, 1e-9);
}

TEST(CurveRegion, RejectsBadInput) {
  const TriangleMesh g = test::grid_mesh(20, 1.0);
  const Points ok = circle(Vec3(0.3, 0.3, 0), 8, 100);
  auto message = [&](const TriangleMesh& m, const Points& c) -> std::string {
    try {
      vertices_inside_curve(m, c);
    } catch (const InvalidInput& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message(g, ok.topRows(2)).find("at least 3"), std::string::npos);
  Points nan = ok;
  nan(5, 1) = std::nan("");
  EXPECT_NE(message(g, nan).find("non-finite"), std::string::npos);
  TriangleMesh bad = g;
  bad.V(3, 0) = std::numeric_limits<double>::infinity();
  EXPECT_NE(message(bad, ok).find("non-finite"), std::string::npos);
  TriangleMesh cloud = g;
  cloud.F.resize(0, 3);
  EXPECT_NE(message(cloud, ok).find("no triangles"), std::string::npos);
  Points line(50, 3);
  for (int i = 0; i < 50; ++i) line.row(i) << i * 0.3, i * 0.1, 0;
  EXPECT_NE(message(g, line).find("collinear"), std::string::npos);
  Points same = Points::Zero(5, 3);
  EXPECT_NE(message(g, same).find("distinct"), std::string::npos);
  // a tiny circle between four vertices encloses none
  EXPECT_NE(message(g, circle(Vec3(0.5, 0.5, 0), 0.2, 40)).find("encloses no vertex"), std::string::npos);
  // far above the surface (another frame)
  EXPECT_NE(message(g, circle(Vec3(0.3, 0.3, 200), 8, 100)).find("from the surface"), std::string::npos);
  Points up = ok;
  up.col(2).array() += 8;  // 8 mm off: accepted only with a larger tolerance
  EXPECT_NO_THROW(vertices_inside_curve(g, up));
  EXPECT_THROW(vertices_inside_curve(g, up, {.max_curve_distance_mm = 5}), InvalidInput);
  EXPECT_THROW(vertices_inside_curve(g, ok, {.max_curve_distance_mm = 0}), InvalidInput);
  CurveVolumeOptions o;
  o.target_edge_mm = -1;
  EXPECT_THROW(curve_volume(g, ok, o), InvalidInput);
}

TEST(CurveRegion, DeterministicAndFast) {
  // ~50k vertices, 500 curve points
  auto bump = [](double x, double y) { return 25 * std::exp(-(x * x + y * y) / (2 * 30.0 * 30.0)); };
  const TriangleMesh g = test::grid_mesh(111, 1.0, bump);
  ASSERT_GT(g.num_vertices(), 49000);
  const Points curve = circle(Vec3(-4.2, 7.9, 0), 70.3, 500, Vec3::UnitX(), Vec3::UnitY(), bump);
  const std::vector<Index> first = vertices_inside_curve(g, curve);
  double best_ms = 1e9;
  for (int rep = 0; rep < 5; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<Index> again = vertices_inside_curve(g, curve);
    best_ms = std::min(best_ms, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    EXPECT_EQ(again, first);
  }
  std::printf("vertices_inside_curve: %d vertices, 500 curve points: %.1f ms (best of 5), %zu inside\n",
              g.num_vertices(), best_ms, first.size());
  EXPECT_LT(best_ms, 200.0);  // a generous bound for shared CI machines
  EXPECT_EQ(curve_volume(g, curve).volume_ml, curve_volume(g, curve).volume_ml);
}

}  // namespace
}  // namespace breastfit::transfer
