// Every blendshape of the default template at its bounds keeps a plausible surface.
#include "breastfit/template/template_blendshapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "breastfit/template/default_template.h"

namespace breastfit::templ {
namespace {

const model::RiggedModel& default_model() {
  static const model::RiggedModel m = build_default_template();
  return m;
}

Points apply(const model::RiggedModel& m, const model::Blendshape& b, double w) {
  Points V = m.rest.V;
  for (size_t k = 0; k < b.vertices.size(); ++k) V.row(b.vertices[k]) += w * b.displacements.row(static_cast<Index>(k));
  return V;
}

double min_quality(const Points& V, const Triangles& F) {
  // 4 sqrt(3) area / sum of squared edge lengths: 1 for equilateral, 0 for degenerate.
  double q = 1;
  for (Index f = 0; f < F.rows(); ++f) {
    const Vec3 a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double s = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
    q = std::min(q, 4.0 * std::sqrt(3.0) * area / s);
  }
  return q;
}

TEST(TemplateBlendshapes, CountNamesAndBounds) {
  const auto& m = default_model();
  EXPECT_GE(m.num_blendshapes(), 55);
  std::set<std::string> names;
  for (const auto& b : m.blendshapes) {
    EXPECT_TRUE(names.insert(b.name).second) << b.name;
    EXPECT_LT(b.lo, b.hi) << b.name;
    EXPECT_LE(b.lo, 0.0) << b.name;
    EXPECT_GE(b.hi, 1.0) << b.name;
    EXPECT_FALSE(b.vertices.empty()) << b.name;
    EXPECT_TRUE(std::is_sorted(b.vertices.begin(), b.vertices.end())) << b.name;
    EXPECT_TRUE(b.displacements.allFinite()) << b.name;
  }
  for (const char* side : {"_R", "_L"})
    for (const char* n : {"breast_volume", "breast_projection", "breast_ptosis", "breast_lateral", "breast_cranial",
                          "breast_upper_pole", "breast_lower_pole", "imf_height", "breast_width", "nipple_lateral",
                          "nipple_height"})
      EXPECT_TRUE(names.count(std::string(n) + side)) << n << side;
  for (const char* n : {"chest_width", "chest_depth", "shoulder_width", "abdomen_protrusion", "waist_width",
                        "back_curvature", "arm_girth_R", "arm_girth_L", "neck_width", "torso_length"})
    EXPECT_TRUE(names.count(n)) << n;
}

TEST(TemplateBlendshapes, PlausibleAtTheirBounds) {
  const auto& m = default_model();
  const double q_rest = min_quality(m.rest.V, m.rest.F);
  // Rest face normals.
  std::vector<Vec3> n0(m.rest.num_faces());
  for (Index f = 0; f < m.rest.num_faces(); ++f) {
    const Vec3 a = m.rest.V.row(m.rest.F(f, 0)), b = m.rest.V.row(m.rest.F(f, 1)), c = m.rest.V.row(m.rest.F(f, 2));
    n0[f] = (b - a).cross(c - a).normalized();
  }
  for (const auto& b : m.blendshapes) {
    double maxd = 0;
    for (Index k = 0; k < b.displacements.rows(); ++k) maxd = std::max(maxd, b.displacements.row(k).norm());
    for (double w : {b.lo, b.hi}) {
      EXPECT_LE(std::abs(w) * maxd, 45.0) << b.name << " at " << w;
      const Points V = apply(m, b, w);
      EXPECT_GT(min_quality(V, m.rest.F), 0.5 * q_rest) << b.name << " at " << w;
      double worst = 1;
      for (Index f = 0; f < m.rest.num_faces(); ++f) {
        const Vec3 a = V.row(m.rest.F(f, 0)), bb = V.row(m.rest.F(f, 1)), c = V.row(m.rest.F(f, 2));
        worst = std::min(worst, (bb - a).cross(c - a).normalized().dot(n0[f]));
      }
      EXPECT_GT(worst, 0.3) << b.name << " at " << w << ": a face turns by more than 72 degrees";
    }
  }
}

TEST(TemplateBlendshapes, SidedShapesMirrorEachOther) {
  const auto& m = default_model();
  std::map<std::array<double, 3>, Index> at;
  for (Index v = 0; v < m.num_vertices(); ++v) at[{m.rest.V(v, 0), m.rest.V(v, 1), m.rest.V(v, 2)}] = v;
  for (const char* n : {"breast_volume", "breast_ptosis", "breast_lateral", "nipple_height", "arm_girth"}) {
    const auto& r = m.blendshapes[*m.blendshape_index(std::string(n) + "_R")];
    const auto& l = m.blendshapes[*m.blendshape_index(std::string(n) + "_L")];
    ASSERT_EQ(r.vertices.size(), l.vertices.size()) << n;
    std::map<Index, Vec3> ld;
    for (size_t k = 0; k < l.vertices.size(); ++k) ld[l.vertices[k]] = l.displacements.row(static_cast<Index>(k));
    for (size_t k = 0; k < r.vertices.size(); ++k) {
      const Index v = r.vertices[k];
      EXPECT_LT(m.rest.V(v, 0), 1e-9) << n;
      const Index mv = at.at({-m.rest.V(v, 0) + 0.0, m.rest.V(v, 1), m.rest.V(v, 2)});
      ASSERT_TRUE(ld.count(mv)) << n;
      const Vec3 d = r.displacements.row(static_cast<Index>(k));
      EXPECT_NEAR((ld[mv] - Vec3(-d.x(), d.y(), d.z())).norm(), 0.0, 1e-6) << n;
    }
  }
}

TEST(TemplateBlendshapes, ShapesAreNotRedundant) {
  // Pairwise cosine similarity of the dense displacement fields stays below 0.8 (the
  // builder orthogonalises overlapping shapes).
  const auto& m = default_model();
  const Index nv = m.num_vertices();
  std::vector<Eigen::VectorXd> d;
  for (const auto& b : m.blendshapes) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(3 * nv);
    for (size_t k = 0; k < b.vertices.size(); ++k)
      x.segment<3>(3 * b.vertices[k]) = b.displacements.row(static_cast<Index>(k)).transpose();
    d.push_back(x.normalized());
  }
  for (size_t i = 0; i < d.size(); ++i)
    for (size_t j = i + 1; j < d.size(); ++j)
      EXPECT_LT(std::abs(d[i].dot(d[j])), 0.8) << m.blendshapes[i].name << " vs " << m.blendshapes[j].name;
}

TEST(TemplateBlendshapes, BreastVolumeGrowsTheBreast) {
  const auto& m = default_model();
  const auto& b = m.blendshapes[*m.blendshape_index("breast_volume_L")];
  const auto& nip = m.landmarks[*m.landmark_index("nipple_L")].point;
  const Vec3 p0 = nip.position(m.rest.V, m.rest.F);
  const Vec3 p1 = nip.position(apply(m, b, 1.0), m.rest.F);
  EXPECT_LT(p1.y(), p0.y() - 3.0);  // moves forwards
  for (Index v : b.vertices) EXPECT_GT(m.rest.V(v, 0), 0.0);
  // Ptosis lowers the nipple.
  const auto& pt = m.blendshapes[*m.blendshape_index("breast_ptosis_L")];
  EXPECT_LT(nip.position(apply(m, pt, 1.0), m.rest.F).z(), p0.z() - 8.0);
}

}  // namespace
}  // namespace breastfit::templ
