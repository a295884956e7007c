#include "breastfit/synth/scan_defects.h"

#include <gtest/gtest.h>

#include "breastfit/mesh/boundary.h"
#include "breastfit/mesh/cleanup.h"
#include "breastfit/mesh/components.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/spatial/closest_point_index.h"
#include "breastfit/mesh/subdivision.h"
#include "support/toy_model.h"

namespace breastfit::synth {
namespace {

TriangleMesh dense_toy() {
  TriangleMesh m = test::make_toy_model().rest;
  for (int k = 0; k < 2; ++k) m = mesh::subdivide(m, true);
  return m;
}

TEST(ScanDefects, HolesAreNewBorderLoopsAwayFromLandmarks) {
  TriangleMesh m = dense_toy();
  const size_t loops_before = mesh::boundary_loops(m).size();
  const std::vector<Vec3> landmarks = {Vec3(0, -40, 120)};
  ArtifactOptions o;
  o.n_holes = 3;
  o.hole_landmark_clearance_mm = 20;
  Rng rng(3);
  const auto holes = punch_holes(m, landmarks, o, rng);
  ASSERT_EQ(holes.size(), 3u);
  mesh::remove_unreferenced_vertices(m);
  EXPECT_EQ(mesh::boundary_loops(m).size(), loops_before + 3);
  for (const Hole& h : holes) {
    EXPECT_GE(h.radius_mm, o.hole_radius_mm.lo);
    EXPECT_LE(h.radius_mm, o.hole_radius_mm.hi);
    EXPECT_GE((h.centre - landmarks[0]).norm(), o.hole_landmark_clearance_mm + h.radius_mm);
    for (Index v = 0; v < m.num_vertices(); ++v)
      EXPECT_GT((m.V.row(v).transpose() - h.centre).norm(), h.radius_mm);
  }
}

TEST(ScanDefects, NoiseHasTheRequestedSize) {
  TriangleMesh m = dense_toy();
  const Points N = mesh::vertex_normals(m);
  ArtifactOptions o;
  o.white_noise_mm = 0.5;
  o.lowfreq_noise_mm = 0.5;
  o.tangential_jitter_mm = 0.0;
  Points V = m.V;
  Rng rng(11);
  add_scan_noise(V, N, o, rng);
  double sum2 = 0, tangential = 0;
  for (Index v = 0; v < V.rows(); ++v) {
    const Vec3 d = (V.row(v) - m.V.row(v)).transpose();
    const double along = d.dot(N.row(v).transpose());
    sum2 += along * along;
    tangential = std::max(tangential, (d - along * N.row(v).transpose()).norm());
  }
  const double rms = std::sqrt(sum2 / V.rows());
  EXPECT_GT(rms, 0.5);   // sqrt(0.5^2 + 0.5^2) = 0.71 expected
  EXPECT_LT(rms, 1.0);
  EXPECT_LT(tangential, 1e-9);
}

TEST(ScanDefects, FragmentsFloatOffTheSurface) {
  const TriangleMesh m = dense_toy();
  const Points N = mesh::vertex_normals(m);
  ArtifactOptions o;
  o.n_fragments = 4;
  Rng rng(2);
  std::vector<Fragment> frags;
  const TriangleMesh f = make_fragments(m, N, o, rng, frags);
  ASSERT_EQ(frags.size(), 4u);
  EXPECT_EQ(mesh::connected_components(f).count(), 4);
  const spatial::ClosestPointIndex index(m);
  for (const Fragment& fr : frags) {
    EXPECT_GE(fr.distance_mm, o.fragment_distance_mm.lo);
    EXPECT_LE(fr.distance_mm, o.fragment_distance_mm.hi);
    EXPECT_GT(index.closest(fr.centre).distance(), 0.5 * o.fragment_distance_mm.lo);
  }
}

TEST(ScanDefects, TableStripsLieFlatBesideTheBodyFacingUp) {
  const TriangleMesh m = dense_toy();
  Rng rng(4);
  const TriangleMesh t = make_table_strips(m.V, rng);
  ASSERT_GT(t.num_faces(), 0);
  EXPECT_EQ(mesh::connected_components(t).count(), 2);
  const Points FN = mesh::face_normals(t);
  for (Index f = 0; f < t.num_faces(); ++f) EXPECT_NEAR(FN(f, 1), -1.0, 1e-9);
  const double x_min = m.V.col(0).minCoeff(), x_max = m.V.col(0).maxCoeff();
  for (Index v = 0; v < t.num_vertices(); ++v) {
    EXPECT_TRUE(t.V(v, 0) < x_min || t.V(v, 0) > x_max);
    EXPECT_GT(t.V(v, 1), m.V.col(1).maxCoeff());
  }
}

TEST(ScanDefects, AppendMeshOffsetsIndices) {
  TriangleMesh a = dense_toy(), b = dense_toy();
  const Index nv = a.num_vertices(), nf = a.num_faces();
  append_mesh(a, b);
  EXPECT_EQ(a.num_vertices(), 2 * nv);
  EXPECT_EQ(a.num_faces(), 2 * nf);
  EXPECT_EQ(a.F(nf, 0), b.F(0, 0) + nv);
}

}  // namespace
}  // namespace breastfit::synth
