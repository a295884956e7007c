// Building blocks of the template: implicit body, marching tetrahedra, clipping, remeshing,
// surface paths, surface queries and heat-diffusion weights, on simple shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/boundary.h"
#include "breastfit/template/body_field.h"
#include "breastfit/template/heat_weights.h"
#include "breastfit/template/iso_surface.h"
#include "breastfit/template/isotropic_remesher.h"
#include "breastfit/template/plane_clip.h"
#include "breastfit/template/surface_paths.h"
#include "breastfit/template/surface_queries.h"

namespace breastfit::templ {
namespace {

TriangleMesh sphere(double r, double step) {
  return marching_tetrahedra([r](const Vec3& p) { return p.norm() - r; }, Vec3::Constant(-r - 2 * step),
                             Vec3::Constant(r + 2 * step), step);
}

TEST(MarchingTetrahedra, SphereIsClosedOrientedAndAccurate) {
  const TriangleMesh m = sphere(50, 5);
  ASSERT_GT(m.num_faces(), 1000);
  EXPECT_TRUE(mesh::boundary_loops(m).empty());
  EXPECT_EQ(mesh::count_non_manifold_edges(m.F), 0);
  double vol = 0;
  for (Index f = 0; f < m.num_faces(); ++f) {
    const Vec3 a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    vol += a.dot(b.cross(c)) / 6.0;
  }
  EXPECT_NEAR(vol, 4.0 / 3.0 * M_PI * 50 * 50 * 50, 0.03 * 4.0 / 3.0 * M_PI * 50 * 50 * 50);  // outward
  for (Index v = 0; v < m.num_vertices(); ++v) EXPECT_NEAR(m.V.row(v).norm(), 50.0, 1.0);
  EXPECT_THROW(sphere(50, -1), InvalidInput);
}

TEST(PlaneClip, CutsASphereAlongThePlane) {
  const TriangleMesh m = sphere(50, 5);
  CutPlane c;
  c.point = Vec3(0, 0, 10);
  c.normal = Vec3::UnitZ();
  const ClippedMesh cm = clip_by_planes(m, {c});
  const auto loops = mesh::boundary_loops(cm.mesh);
  ASSERT_EQ(loops.size(), 1u);
  for (Index v : loops[0]) {
    EXPECT_NEAR(cm.mesh.V(v, 2), 10.0, 1e-9);
    EXPECT_EQ(cm.on_cut[v], 1u);
  }
  for (Index v = 0; v < cm.mesh.num_vertices(); ++v) EXPECT_LE(cm.mesh.V(v, 2), 10.0 + 1e-9);
}

TEST(PlaneClip, RegionLimitsTheCut) {
  CutPlane c;
  c.point = Vec3(0, 0, 0);
  c.normal = Vec3::UnitZ();
  c.region_point = Vec3(100, 0, 0);
  c.region_dir = Vec3::UnitZ();
  c.region_radius = 10;
  EXPECT_FALSE(c.removes(Vec3(0, 0, 5)));
  EXPECT_TRUE(c.removes(Vec3(100, 5, 5)));
  EXPECT_FALSE(c.removes(Vec3(100, 5, -5)));
}

TEST(BodyField, DefaultBodyIsSymmetricAndDistanceLike) {
  const BodyField f{BodyParams{}};
  for (const Vec3& p : {Vec3(50, -30, -150), Vec3(120, 40, -20), Vec3(-170, 30, -100), Vec3(10, 60, 20)})
    EXPECT_NEAR(f.value(p), f.value(Vec3(-p.x(), p.y(), p.z())), 1e-12);
  // Inside the chest, outside in front of it.
  EXPECT_LT(f.value(Vec3(0, 30, -150)), -50);
  EXPECT_GT(f.value(Vec3(0, -150, -150)), 50);
  // Projection lands on the zero set with a unit-ish gradient.
  const Vec3 p = f.project(Vec3(0, -80, -250));
  EXPECT_NEAR(f.value(p), 0.0, 1e-6);
  EXPECT_NEAR(f.gradient(p).norm(), 1.0, 0.3);
  // The breasts lie in front of the chest wall.
  const Vec3 n = f.breast_frame(1).nipple;
  EXPECT_NEAR(f.value(n), 0.0, 0.5);
  EXPECT_GT(f.value_without_breasts(n), 30.0);
  EXPECT_GT(n.x(), 60.0);
  EXPECT_LT(f.breast_frame(0).nipple.x(), -60.0);
  BodyParams bad;
  bad.trunk.resize(2);
  EXPECT_THROW(BodyField{bad}, InvalidInput);
}

TEST(IsotropicRemesh, ReachesTheTargetEdgeOnAClippedBody) {
  BodyParams P;
  const BodyField f(P);
  const TriangleMesh iso = marching_tetrahedra([&](const Vec3& p) { return f.value(p); },
                                               Vec3(-20, -160, -380), Vec3(320, 190, 100), 8.0);
  const std::vector<CutPlane> cuts = f.cut_planes();
  const ClippedMesh cm = clip_by_planes(iso, cuts);
  RemeshOptions o;
  o.target_edge_mm = 20;
  const ClippedMesh r = isotropic_remesh(cm, f, cuts, o);
  std::vector<double> len;
  for (Index t = 0; t < r.mesh.num_faces(); ++t)
    for (int c = 0; c < 3; ++c) len.push_back((r.mesh.V.row(r.mesh.F(t, c)) - r.mesh.V.row(r.mesh.F(t, (c + 1) % 3))).norm());
  std::sort(len.begin(), len.end());
  EXPECT_NEAR(len[len.size() / 2], 20.0, 4.0);
  EXPECT_EQ(mesh::count_non_manifold_edges(r.mesh.F), 0);
  for (Index v = 0; v < r.mesh.num_vertices(); ++v) {
    EXPECT_NEAR(f.value(r.mesh.V.row(v).transpose()), 0.0, 1e-3);
    for (size_t c = 0; c < cuts.size(); ++c)
      if (r.on_cut[v] & (1u << c)) EXPECT_NEAR(cuts[c].signed_distance(r.mesh.V.row(v).transpose()), 0.0, 1e-6);
  }
  EXPECT_THROW(isotropic_remesh(cm, f, cuts, RemeshOptions{0.0, 3, 1}), InvalidInput);
}

TEST(SurfacePaths, EquatorOfASphere) {
  const TriangleMesh m = sphere(40, 4);
  Eigen::VectorXd z = m.V.col(2);
  const auto lines = iso_lines(m, z, 5.0);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_TRUE(lines[0].closed);
  const double r = std::sqrt(40.0 * 40.0 - 25.0);
  EXPECT_NEAR(path_length(m, lines[0]), 2 * M_PI * r, 0.03 * 2 * M_PI * r);
  const auto pts = resample_path(m, lines[0], 5.0);
  EXPECT_NEAR(static_cast<double>(pts.size()), 2 * M_PI * r / 5.0, 3.0);
  for (const auto& sp : pts) {
    EXPECT_NEAR(sp.position(m.V, m.F).z(), 5.0, 1e-9);
    EXPECT_NEAR(sp.bary.sum(), 1.0, 1e-12);
  }
  EXPECT_THROW(iso_lines(m, Eigen::VectorXd::Zero(3), 0.0), InvalidInput);
}

TEST(SurfacePaths, EdgePathFollowsMeshEdges) {
  const TriangleMesh m = sphere(30, 5);
  const Index a = m.F(0, 0), b = m.F(0, 1), c = m.F(0, 2);
  const SurfacePath p = edge_path(m, {a, b, c});
  ASSERT_EQ(p.segments.size(), 2u);
  EXPECT_NEAR((segment_point(m, p.segments[0], 0) - m.V.row(a).transpose()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((segment_point(m, p.segments[1], 1) - m.V.row(c).transpose()).norm(), 0.0, 1e-12);
  const SurfacePath r = reversed(p);
  EXPECT_NEAR((segment_point(m, r.segments[0], 0) - m.V.row(c).transpose()).norm(), 0.0, 1e-12);
  // Two far-apart vertices share no edge.
  Index far = 0;
  for (Index v = 0; v < m.num_vertices(); ++v)
    if ((m.V.row(v) - m.V.row(a)).norm() > (m.V.row(far) - m.V.row(a)).norm()) far = v;
  EXPECT_THROW(edge_path(m, {a, far}), InvalidInput);
}

TEST(SurfaceQueries, ClosestPointAndRayHit) {
  const TriangleMesh m = sphere(30, 3);
  const SurfacePoint cp = closest_surface_point(m, Vec3(0, 0, 100));
  EXPECT_NEAR(cp.position(m.V, m.F).z(), 30.0, 0.5);
  const auto hit = first_ray_hit(m, Vec3::Zero(), Vec3::UnitX(), 100);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->position(m.V, m.F).x(), 30.0, 0.5);
  EXPECT_FALSE(first_ray_hit(m, Vec3(0, 0, 100), Vec3::UnitZ(), 100).has_value());
}

TEST(SurfaceQueries, ClosestPointOnDegenerateTriangleIsOnItsEdges) {
  // A collinear triangle (face 0) hides nothing: the answer lies on its longest edge.
  TriangleMesh m;
  m.V.resize(3, 3);
  m.V << 0, 0, 0, 1, 0, 0, 3, 0, 0;
  m.F.resize(1, 3);
  m.F << 0, 1, 2;
  const SurfacePoint cp = closest_surface_point(m, Vec3(2, 1, 0));
  EXPECT_EQ(cp.face, 0);
  EXPECT_NEAR((cp.position(m.V, m.F) - Vec3(2, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(cp.bary.sum(), 1.0, 1e-12);
}

TEST(HeatWeights, PartitionOfUnityAndSmoothness) {
  const TriangleMesh m = sphere(60, 6);
  Eigen::MatrixXd seeds = Eigen::MatrixXd::Zero(m.num_vertices(), 3);
  for (Index v = 0; v < m.num_vertices(); ++v) seeds(v, m.V(v, 2) > 20 ? 0 : (m.V(v, 2) < -20 ? 1 : 2)) = 1;
  const auto W = heat_diffusion_weights(m, seeds, {300.0, 2, 0.01});
  const Eigen::MatrixXd D(W);
  for (Index v = 0; v < m.num_vertices(); ++v) {
    EXPECT_NEAR(D.row(v).sum(), 1.0, 1e-12);
    EXPECT_GE(D.row(v).minCoeff(), 0.0);
    EXPECT_LE((D.row(v).array() > 0).count(), 2);
  }
  // Top vertex mostly bone 0, bottom mostly bone 1.
  Index top = 0, bottom = 0;
  for (Index v = 0; v < m.num_vertices(); ++v) {
    if (m.V(v, 2) > m.V(top, 2)) top = v;
    if (m.V(v, 2) < m.V(bottom, 2)) bottom = v;
  }
  EXPECT_GT(D(top, 0), 0.9);
  EXPECT_GT(D(bottom, 1), 0.9);
  // The Laplacian annihilates constants and the areas sum to the sphere area.
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(m.num_vertices());
  EXPECT_LT((cotan_laplacian(m) * ones).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(vertex_areas(m).sum(), 4 * M_PI * 60 * 60, 0.03 * 4 * M_PI * 60 * 60);
}

}  // namespace
}  // namespace breastfit::templ
