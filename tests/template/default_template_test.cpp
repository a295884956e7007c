// Tests of the default template: determinism, mesh, cuts, weights, landmarks, distances, drawings.
#include "breastfit/template/default_template.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/boundary.h"
#include "breastfit/mesh/landmark_names.h"

namespace breastfit::templ {
namespace {

const model::RiggedModel& default_model() {
  static const model::RiggedModel m = build_default_template();
  return m;
}

Vec3 landmark(const model::RiggedModel& m, const std::string& name) {
  const auto i = m.landmark_index(name);
  EXPECT_TRUE(i.has_value()) << name;
  return m.landmarks.at(*i).point.position(m.rest.V, m.rest.F);
}

TEST(DefaultTemplate, PassesValidate) { EXPECT_NO_THROW(default_model().validate()); }

TEST(DefaultTemplate, IsDeterministic) {
  const model::RiggedModel a = build_default_template();
  const model::RiggedModel& b = default_model();
  ASSERT_EQ(a.rest.V.rows(), b.rest.V.rows());
  EXPECT_TRUE(a.rest.V == b.rest.V);
  EXPECT_TRUE(a.rest.F == b.rest.F);
  EXPECT_EQ(Eigen::MatrixXd(a.weights), Eigen::MatrixXd(b.weights));
  ASSERT_EQ(a.blendshapes.size(), b.blendshapes.size());
  for (size_t k = 0; k < a.blendshapes.size(); ++k) {
    EXPECT_EQ(a.blendshapes[k].name, b.blendshapes[k].name);
    EXPECT_EQ(a.blendshapes[k].vertices, b.blendshapes[k].vertices);
    EXPECT_TRUE(a.blendshapes[k].displacements == b.blendshapes[k].displacements);
  }
  ASSERT_EQ(a.landmarks.size(), b.landmarks.size());
  for (size_t k = 0; k < a.landmarks.size(); ++k) {
    EXPECT_EQ(a.landmarks[k].point.face, b.landmarks[k].point.face);
    EXPECT_TRUE(a.landmarks[k].point.bary == b.landmarks[k].point.bary);
  }
  ASSERT_EQ(a.drawings.size(), b.drawings.size());
  for (size_t k = 0; k < a.drawings.size(); ++k) {
    ASSERT_EQ(a.drawings[k].points.size(), b.drawings[k].points.size());
    for (size_t i = 0; i < a.drawings[k].points.size(); ++i) {
      EXPECT_EQ(a.drawings[k].points[i].face, b.drawings[k].points[i].face);
      EXPECT_TRUE(a.drawings[k].points[i].bary == b.drawings[k].points[i].bary);
    }
  }
}

TEST(DefaultTemplate, VertexCountInRange) {
  const auto& m = default_model();
  EXPECT_GE(m.num_vertices(), 2000);
  EXPECT_LE(m.num_vertices(), 3000);
}

TEST(DefaultTemplate, MeshIsManifoldOrientedAndWellShaped) {
  const auto& m = default_model();
  std::map<std::pair<Index, Index>, int> directed;
  double min_angle = 180;
  for (Index f = 0; f < m.rest.num_faces(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const Index a = m.rest.F(f, c), b = m.rest.F(f, (c + 1) % 3);
      EXPECT_NE(a, b);
      ++directed[{a, b}];
      const Vec3 p = m.rest.V.row(a), q = m.rest.V.row(b), r = m.rest.V.row(m.rest.F(f, (c + 2) % 3));
      const double ang = std::acos(std::clamp((q - p).normalized().dot((r - p).normalized()), -1.0, 1.0));
      min_angle = std::min(min_angle, ang * 180 / M_PI);
    }
  }
  for (const auto& [e, n] : directed) EXPECT_EQ(n, 1) << "directed edge used twice: inconsistent orientation";
  EXPECT_EQ(mesh::count_non_manifold_edges(m.rest.F), 0);
  EXPECT_GT(min_angle, 12.0);
  // Edge lengths near the 16 mm target.
  std::vector<double> len;
  for (const auto& [e, n] : directed)
    if (e.first < e.second) len.push_back((m.rest.V.row(e.first) - m.rest.V.row(e.second)).norm());
  std::sort(len.begin(), len.end());
  EXPECT_NEAR(len[len.size() / 2], 16.0, 3.0);
  // Outward orientation: the signed volume of the open torso closed by its cuts is positive when
  // the normals point outwards; approximate with the divergence about the trunk axis.
  double flux = 0;
  for (Index f = 0; f < m.rest.num_faces(); ++f) {
    const Vec3 a = m.rest.V.row(m.rest.F(f, 0)), b = m.rest.V.row(m.rest.F(f, 1)), c = m.rest.V.row(m.rest.F(f, 2));
    const Vec3 n = (b - a).cross(c - a);
    Vec3 ctr = (a + b + c) / 3;
    ctr.z() = 0;
    ctr.y() -= 30;
    flux += n.dot(ctr);
  }
  EXPECT_GT(flux, 0);
}

TEST(DefaultTemplate, HasFourCutLoops) {
  const auto& m = default_model();
  const auto loops = mesh::boundary_loops(m.rest);
  ASSERT_EQ(loops.size(), 4u);
  int waist = 0, neck = 0, arm_r = 0, arm_l = 0;
  for (const auto& loop : loops) {
    Vec3 c = Vec3::Zero();
    for (Index v : loop) c += m.rest.V.row(v).transpose();
    c /= static_cast<double>(loop.size());
    if (c.z() < -300) ++waist;
    else if (c.z() > 10) ++neck;
    else if (c.x() < -150) ++arm_r;
    else if (c.x() > 150) ++arm_l;
  }
  EXPECT_EQ(waist, 1);
  EXPECT_EQ(neck, 1);
  EXPECT_EQ(arm_r, 1);
  EXPECT_EQ(arm_l, 1);
}

TEST(DefaultTemplate, IsLeftRightSymmetric) {
  const auto& m = default_model();
  std::set<std::array<double, 3>> pts;
  for (Index v = 0; v < m.num_vertices(); ++v) pts.insert({m.rest.V(v, 0), m.rest.V(v, 1), m.rest.V(v, 2)});
  for (Index v = 0; v < m.num_vertices(); ++v)
    EXPECT_TRUE(pts.count({-m.rest.V(v, 0) + 0.0, m.rest.V(v, 1), m.rest.V(v, 2)})) << v;
}

TEST(DefaultTemplate, HasNineBonesInOrder) {
  const auto& m = default_model();
  const std::vector<std::string> names = {"abdomen",    "thorax",      "neck",        "clavicle_R", "clavicle_L",
                                          "upper_arm_R", "upper_arm_L", "breast_R",    "breast_L"};
  ASSERT_EQ(m.num_bones(), 9);
  for (int j = 0; j < 9; ++j) EXPECT_EQ(m.bones[j].name, names[j]);
  EXPECT_FALSE(m.bones[0].parent.has_value());
  EXPECT_EQ(*m.bones[*m.bone_index("upper_arm_R")].parent, *m.bone_index("clavicle_R"));
  EXPECT_EQ(*m.bones[*m.bone_index("breast_L")].parent, *m.bone_index("thorax"));
  // Upper arm: first axis along the humerus (down and lateral); breast pivot on the chest front.
  const auto& arm = m.bones[*m.bone_index("upper_arm_L")];
  EXPECT_LT(arm.axes.col(0).z(), -0.8);
  EXPECT_GT(arm.axes.col(0).x(), 0.25);
  const auto& br = m.bones[*m.bone_index("breast_R")];
  EXPECT_LT(br.pivot.x(), -50);
  EXPECT_LT(br.pivot.y(), 0);
  for (const auto& b : m.bones) EXPECT_NEAR(b.axes.determinant(), 1.0, 1e-9) << b.name;
}

TEST(DefaultTemplate, WeightsAreNormalisedSparseAndSmooth) {
  const auto& m = default_model();
  const Eigen::MatrixXd W(m.weights);
  for (Index v = 0; v < m.num_vertices(); ++v) {
    EXPECT_NEAR(W.row(v).sum(), 1.0, 1e-9);
    EXPECT_GE(W.row(v).minCoeff(), 0.0);
    EXPECT_LE((W.row(v).array() > 0).count(), 4);
  }
  double worst = 0;
  for (Index f = 0; f < m.rest.num_faces(); ++f)
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, (W.row(m.rest.F(f, c)) - W.row(m.rest.F(f, (c + 1) % 3))).cwiseAbs().maxCoeff());
  EXPECT_LT(worst, 0.5);
  // Nipples follow their breast bones; arm cut vertices follow the upper arms.
  const auto nip = m.landmarks[*m.landmark_index("nipple_R")].point;
  const Index v = m.rest.F(nip.face, 0);
  EXPECT_GT(W(v, *m.bone_index("breast_R")), 0.6);
  Index lowest_arm = -1;
  for (Index u = 0; u < m.num_vertices(); ++u)
    if (m.rest.V(u, 0) > 150 && (lowest_arm < 0 || m.rest.V(u, 2) < m.rest.V(lowest_arm, 2))) lowest_arm = u;
  ASSERT_GE(lowest_arm, 0);
  EXPECT_GT(W(lowest_arm, *m.bone_index("upper_arm_L")), 0.8);
}

TEST(DefaultTemplate, LandmarksOnTheirSides) {
  const auto& m = default_model();
  ASSERT_EQ(m.landmarks.size(), kLandmarkNames.size());
  for (size_t i = 0; i < kLandmarkNames.size(); ++i) {
    EXPECT_EQ(m.landmarks[i].name, kLandmarkNames[i]);
    const auto& sp = m.landmarks[i].point;
    ASSERT_GE(sp.face, 0);
    ASSERT_LT(sp.face, m.rest.num_faces());
    EXPECT_NEAR(sp.bary.sum(), 1.0, 1e-9);
    EXPECT_GE(sp.bary.minCoeff(), -1e-12);
    const Vec3 p = sp.position(m.rest.V, m.rest.F);
    const std::string n(kLandmarkNames[i]);
    if (n.ends_with("_R")) EXPECT_LT(p.x(), -20) << n;
    else if (n.ends_with("_L")) EXPECT_GT(p.x(), 20) << n;
    else EXPECT_NEAR(p.x(), 0.0, 1e-9) << n;
    const Vec3 q = landmark(m, mirrored_landmark_name(n));
    EXPECT_NEAR((p - Vec3(-q.x(), q.y(), q.z())).norm(), 0.0, 1e-6) << n;
  }
}

TEST(DefaultTemplate, AnatomicalDistances) {
  const auto& m = default_model();
  const Vec3 notch = landmark(m, "sternal_notch"), xiph = landmark(m, "xiphoid");
  const Vec3 nr = landmark(m, "nipple_R"), nl = landmark(m, "nipple_L");
  const Vec3 ar = landmark(m, "acromion_R"), al = landmark(m, "acromion_L");
  const Vec3 mr = landmark(m, "midaxillary_R");
  const Vec3 lr = landmark(m, "lowest_breast_R");
  EXPECT_GE((xiph - notch).norm(), 200.0);
  EXPECT_LE((xiph - notch).norm(), 225.0);
  EXPECT_GE((nl - nr).norm(), 170.0);
  EXPECT_LE((nl - nr).norm(), 210.0);
  EXPECT_GE((al - ar).norm(), 340.0);
  EXPECT_LE((al - ar).norm(), 380.0);
  EXPECT_GE(notch.z() - nr.z(), 160.0);  // nipples 16-25 cm below the notch
  EXPECT_LE((nr - notch).norm(), 260.0);
  EXPECT_LT(lr.z(), nr.z() - 25.0);    // the lowest breast point is below the nipple
  EXPECT_LT(nr.y(), xiph.y() - 15.0);  // nipples in front of the sternum
  EXPECT_GT(mr.y(), nr.y() + 80.0);    // mid-axillary well behind the nipple
  // Chest width at the axilla, torso depth, waist narrower than the chest.
  auto width_at = [&](double z) {
    double lo = 0, hi = 0;
    for (Index v = 0; v < m.num_vertices(); ++v) {
      if (std::abs(m.rest.V(v, 2) - z) > 10) continue;
      lo = std::min(lo, m.rest.V(v, 0));
      hi = std::max(hi, m.rest.V(v, 0));
    }
    return hi - lo;
  };
  // Chest width at the axilla: between the mid-axillary points (bench subjects 266-322 mm).
  const double chest = (landmark(m, "midaxillary_L") - mr).norm();
  EXPECT_GE(chest, 270.0);
  EXPECT_LE(chest, 340.0);
  const double waist = width_at(-290.0);
  EXPECT_LT(waist, chest - 20.0);
  double ymin = 0, ymax = 0;
  for (Index v = 0; v < m.num_vertices(); ++v) {
    if (std::abs(m.rest.V(v, 2) - nr.z()) > 10) continue;
    ymin = std::min(ymin, m.rest.V(v, 1));
    ymax = std::max(ymax, m.rest.V(v, 1));
  }
  EXPECT_GE(ymax - ymin, 190.0);
  EXPECT_LE(ymax - ymin, 250.0);
}

TEST(DefaultTemplate, DrawingsAreOnTheSurfaceAndWellFormed) {
  const auto& m = default_model();
  const std::map<std::string, bool> expected = {{"breast_contour_R", true}, {"breast_contour_L", true},
                                                {"sternum", false},         {"imf_R", false},
                                                {"imf_L", false}};
  for (const auto& [name, closed] : expected) {
    const auto i = m.drawing_index(name);
    ASSERT_TRUE(i.has_value()) << name;
    const auto& d = m.drawings[*i];
    EXPECT_EQ(d.closed, closed) << name;
    ASSERT_GE(d.points.size(), 10u) << name;
    std::vector<Vec3> P;
    for (const auto& sp : d.points) {
      ASSERT_GE(sp.face, 0);
      ASSERT_LT(sp.face, m.rest.num_faces());
      EXPECT_NEAR(sp.bary.sum(), 1.0, 1e-9);
      EXPECT_GE(sp.bary.minCoeff(), -1e-12);
      P.push_back(sp.position(m.rest.V, m.rest.F));
    }
    for (size_t k = 0; k + 1 < P.size(); ++k) {
      const double s = (P[k + 1] - P[k]).norm();
      EXPECT_GT(s, 1.5) << name << " " << k;
      EXPECT_LT(s, 7.0) << name << " " << k;
    }
    if (name.starts_with("breast_contour")) {
      // Starts at its most superior point, counter-clockwise seen from the front (x right, z up).
      double zmax = -1e9, area = 0;
      for (size_t k = 0; k < P.size(); ++k) {
        zmax = std::max(zmax, P[k].z());
        const Vec3& a = P[k];
        const Vec3& b = P[(k + 1) % P.size()];
        area += a.x() * b.z() - b.x() * a.z();
      }
      EXPECT_NEAR(P[0].z(), zmax, 3.0) << name;
      EXPECT_GT(area, 0) << name;
      const double s = name.ends_with("_R") ? -1 : 1;
      double xmin = 1e9, xmax = -1e9, zmin = 1e9;
      for (const auto& p : P) {
        xmin = std::min(xmin, s * p.x());
        xmax = std::max(xmax, s * p.x());
        zmin = std::min(zmin, p.z());
      }
      EXPECT_GT(xmin, 10);     // medial border beside the sternum
      EXPECT_LT(xmin, 45);
      EXPECT_GT(xmax, 125);    // lateral border at the anterior axillary line
      EXPECT_LT(xmax, 175);
      EXPECT_GT(zmax, -135);   // from about the 2nd rib...
      EXPECT_LT(zmax, -75);
      EXPECT_GT(zmin, -290);   // ... to the inframammary fold
      EXPECT_LT(zmin, -235);
    }
    if (name == "sternum") {
      for (const auto& p : P) EXPECT_NEAR(p.x(), 0.0, 1e-9);
      EXPECT_NEAR((P.front() - landmark(m, "sternal_notch")).norm(), 0.0, 1e-6);
      EXPECT_NEAR((P.back() - landmark(m, "xiphoid")).norm(), 0.0, 1e-6);
    }
    if (name.starts_with("imf")) {
      // From the medial-most to the lateral-most point through the lowest.
      EXPECT_LT(std::abs(P.front().x()), std::abs(P.back().x()) - 60) << name;
      const Vec3 low = landmark(m, name == "imf_R" ? "lowest_breast_R" : "lowest_breast_L");
      double best = 1e9;
      for (const auto& p : P) best = std::min(best, (p - low).norm());
      EXPECT_LT(best, 15.0) << name;
    }
  }
}

TEST(DefaultTemplate, HasBreastRegions) {
  const auto& m = default_model();
  for (const char* n : {"breast_R", "breast_L"}) {
    const auto i = m.region_index(n);
    ASSERT_TRUE(i.has_value()) << n;
    const auto& r = m.regions[*i];
    EXPECT_GT(r.vertices.size(), 60u);
    for (Index v : r.vertices) EXPECT_EQ(m.rest.V(v, 0) < 0, std::string(n) == "breast_R");
  }
}

TEST(DefaultTemplate, RejectsBadOptions) {
  DefaultTemplateOptions o;
  o.target_edge_mm = 2;
  EXPECT_THROW(build_default_template(o), InvalidInput);
  o = {};
  o.body.breast[0].depth += 5;  // asymmetric
  EXPECT_THROW(build_default_template(o), InvalidInput);
  o = {};
  o.generic_modes = -1;
  EXPECT_THROW(build_default_template(o), InvalidInput);
}

TEST(DefaultTemplate, CoarserOptionGivesFewerVertices) {
  DefaultTemplateOptions o;
  o.target_edge_mm = 24;
  o.generic_modes = 2;
  const auto m = build_default_template(o);
  EXPECT_LT(m.num_vertices(), default_model().num_vertices() / 2 + 200);
  EXPECT_EQ(m.num_blendshapes(), default_model().num_blendshapes() - 18);
  EXPECT_NO_THROW(m.validate());
}

}  // namespace
}  // namespace breastfit::templ
