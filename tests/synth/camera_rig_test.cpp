#include "breastfit/synth/camera_rig.h"

#include <gtest/gtest.h>

#include "breastfit/mesh/normals.h"
#include "breastfit/mesh/subdivision.h"

namespace breastfit::synth {
namespace {

/// Unit-ish sphere (radius r) as a subdivided octahedron, outward triangles.
TriangleMesh sphere(double r, int steps) {
  TriangleMesh m;
  m.V.resize(6, 3);
  m.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  m.F.resize(8, 3);
  m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  for (int k = 0; k < steps; ++k) m = mesh::subdivide(m, false);
  for (Index v = 0; v < m.num_vertices(); ++v) m.V.row(v) = r * m.V.row(v).normalized();
  return m;
}

TEST(CameraRig, RingsAroundTheCentre) {
  ScannerOptions o;
  o.n_azimuth = 7;
  o.elevations_deg = {-10, 20};
  const Vec3 c(10, 20, 30);
  const auto cams = camera_rig(o, PoseType::Standing, c);
  ASSERT_EQ(cams.size(), 14u);
  for (const auto& cam : cams) {
    EXPECT_NEAR((cam.position - c).norm(), o.distance_mm, 1e-9);
    EXPECT_NEAR(cam.forward.dot((c - cam.position).normalized()), 1.0, 1e-12);
    EXPECT_NEAR(cam.right.dot(cam.forward), 0.0, 1e-12);
    EXPECT_NEAR(cam.up.dot(cam.forward), 0.0, 1e-12);
  }
  // The middle camera of the first ring is in front of the body (-y) and below the centre.
  EXPECT_LT(cams[3].position.y(), c.y() - 0.9 * o.distance_mm);
  EXPECT_LT(cams[3].position.z(), c.z());
  EXPECT_GT(cams[10].position.z(), c.z());
  // Azimuths go from patient right (-x) to left (+x).
  EXPECT_LT(cams[0].position.x(), c.x());
  EXPECT_GT(cams[6].position.x(), c.x());
}

TEST(CameraRig, SupineNeverSeesTheBack) {
  const TriangleMesh s = sphere(100.0, 4);
  const Points N = mesh::vertex_normals(s);
  ScannerOptions o;
  o.arc_deg_supine = 160;
  const auto cams = camera_rig(o, PoseType::Supine, Vec3::Zero());
  const auto views = count_views(s, N, cams, o, 1);
  int front_seen = 0, front = 0;
  for (Index v = 0; v < s.num_vertices(); ++v) {
    // Arc +-80 deg and incidence < 75 deg: normals more than 155 deg from anterior are never seen.
    if (s.V(v, 1) > 95.0) EXPECT_EQ(views[static_cast<size_t>(v)], 0) << "posterior vertex seen";
    if (s.V(v, 1) < -50.0) {
      ++front;
      front_seen += views[static_cast<size_t>(v)] > 0;
    }
  }
  EXPECT_EQ(front_seen, front);
}

TEST(CameraRig, OcclusionHidesWhatIsBehind) {
  // A small sphere hidden behind a big one for a single frontal camera.
  TriangleMesh big = sphere(100.0, 3), small = sphere(20.0, 3);
  for (Index v = 0; v < small.num_vertices(); ++v) small.V(v, 1) += 300.0;  // behind (posterior)
  TriangleMesh both = big;
  const Index nv = both.num_vertices();
  both.V.conservativeResize(nv + small.num_vertices(), 3);
  both.V.bottomRows(small.num_vertices()) = small.V;
  both.F.conservativeResize(both.num_faces() + small.num_faces(), 3);
  both.F.bottomRows(small.num_faces()) = small.F.array() + nv;
  const Points N = mesh::vertex_normals(both);
  ScannerOptions o;
  o.n_azimuth = 1;
  o.elevations_deg = {0.0};
  o.max_incidence_deg = 89.0;
  const auto cams = camera_rig(o, PoseType::Standing, Vec3::Zero());
  const auto views = count_views(both, N, cams, o, 1);
  int small_front_seen = 0;
  for (Index v = nv; v < both.num_vertices(); ++v) small_front_seen += views[static_cast<size_t>(v)];
  EXPECT_EQ(small_front_seen, 0);
  EXPECT_EQ(views[3], 1);  // vertex (0, -100, 0) faces the camera
}

}  // namespace
}  // namespace breastfit::synth
