#include "breastfit/model/pose_evaluator.h"

#include <gtest/gtest.h>

#include <set>

#include "breastfit/core/errors.h"
#include "support/default_template.h"
#include "support/toy_model.h"

namespace breastfit::model {
namespace {

constexpr double kStep = 1e-6;

/// Dense 3 by P matrix of a sparse point Jacobian; checks that parameter indices are unique.
Eigen::Matrix<double, 3, Eigen::Dynamic> dense(const PointJacobian& J, int num_params) {
  EXPECT_EQ(J.params.size(), J.columns.size());
  std::set<int> seen;
  Eigen::Matrix<double, 3, Eigen::Dynamic> D = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, num_params);
  for (size_t e = 0; e < J.params.size(); ++e) {
    EXPECT_TRUE(seen.insert(J.params[e]).second) << "duplicate parameter " << J.params[e];
    EXPECT_GE(J.params[e], 0);
    EXPECT_LT(J.params[e], num_params);
    D.col(J.params[e]) = J.columns[e];
  }
  return D;
}

/// Column q of the central finite difference of `f` (a function of the posed evaluator returning
/// a stacked vector) through ParamLayout::apply_increment.
template <class F>
Eigen::MatrixXd finite_difference(const RiggedModel& m, const PoseParams& p, F f) {
  PoseEvaluator e(m);
  const ParamLayout& layout = e.layout();
  Eigen::MatrixXd J;
  for (int q = 0; q < layout.num_params(); ++q) {
    Eigen::VectorXd delta = Eigen::VectorXd::Zero(layout.num_params());
    delta[q] = kStep;
    PoseParams plus = p, minus = p;
    layout.apply_increment(m, delta, plus);
    layout.apply_increment(m, -delta, minus);
    e.set_params(plus);
    const Eigen::VectorXd fp = f(e);
    e.set_params(minus);
    const Eigen::VectorXd fm = f(e);
    if (q == 0) J.resize(fp.size(), layout.num_params());
    J.col(q) = (fp - fm) / (2 * kStep);
  }
  return J;
}

/// max over columns of |analytic − numeric| / max(|numeric|, 1).
double max_relative_error(const Eigen::MatrixXd& A, const Eigen::MatrixXd& N) {
  double worst = 0;
  for (Eigen::Index c = 0; c < A.cols(); ++c)
    worst = std::max(worst, (A.col(c) - N.col(c)).norm() / std::max(N.col(c).norm(), 1.0));
  return worst;
}

/// Direct evaluation of docs/MODEL.md (reference for the evaluator).
Points naive_pose(const RiggedModel& m, const PoseParams& p) {
  Points out(m.num_vertices(), 3);
  for (Index i = 0; i < m.num_vertices(); ++i) {
    Vec3 B = m.rest.V.row(i).transpose();
    for (int k = 0; k < m.num_blendshapes(); ++k) {
      const auto& s = m.blendshapes[k];
      for (size_t r = 0; r < s.vertices.size(); ++r)
        if (s.vertices[r] == i) B += p.alpha[k] * s.displacements.row(r).transpose();
    }
    Vec3 x = Vec3::Zero();
    for (int j = 0; j < m.num_bones(); ++j) {
      const double w = m.weights.coeff(i, j);
      const Bone& b = m.bones[j];
      const BonePose& bp = p.bones[j];
      x += w * (bp.rotation.toRotationMatrix() * b.axes * bp.scale.asDiagonal() * b.axes.transpose() *
                    (B - b.pivot) +
                b.pivot + bp.translation);
    }
    out.row(i) = p.global.apply(x).transpose();
  }
  return out;
}

class PoseEvaluatorTest : public ::testing::Test {
 protected:
  RiggedModel model = test::make_toy_model();
};

TEST_F(PoseEvaluatorTest, IdentityReproducesRestMesh) {
  PoseEvaluator e(model);
  e.set_params(PoseParams::identity(model));
  EXPECT_LT((e.vertices() - model.rest.V).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LT((pose_vertices(model, PoseParams::identity(model)) - model.rest.V).cwiseAbs().maxCoeff(), 1e-10);
}

TEST_F(PoseEvaluatorTest, MatchesDirectFormula) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const PoseParams p = test::random_toy_pose(model, seed);
    const Points posed = pose_vertices(model, p);
    const Points ref = naive_pose(model, p);
    EXPECT_LT((posed - ref).cwiseAbs().maxCoeff(), 1e-9) << "seed " << seed;
    EXPECT_GT((posed - model.rest.V).cwiseAbs().maxCoeff(), 5.0) << "pose should be non-trivial";
  }
}

TEST_F(PoseEvaluatorTest, VertexJacobianMatchesFiniteDifferences) {
  for (std::uint64_t seed : {11u, 12u, 13u}) {
    const PoseParams p = test::random_toy_pose(model, seed);
    const Eigen::MatrixXd N = finite_difference(model, p, [](const PoseEvaluator& e) {
      return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(e.vertices().data(), e.vertices().size()));
    });
    PoseEvaluator e(model);
    e.set_params(p);
    const int P = e.layout().num_params();
    Eigen::MatrixXd A(3 * model.num_vertices(), P);
    PointJacobian J;
    size_t max_entries = 0;
    for (Index i = 0; i < model.num_vertices(); ++i) {
      e.vertex_jacobian(i, J);
      max_entries = std::max(max_entries, J.params.size());
      A.middleRows(3 * i, 3) = dense(J, P);
    }
    EXPECT_GE(max_entries, 7u + 3 * 9 + 2) << "some vertices should have 3 bones and 2 shapes";
    EXPECT_LT(max_relative_error(A, N), 1e-6) << "seed " << seed;
  }
}

TEST_F(PoseEvaluatorTest, VertexJacobianWithoutBlendshapesKeepsTheOtherEntries) {
  PoseEvaluator e(model);
  e.set_params(test::random_toy_pose(model, 14));
  const int first_shape = e.layout().blendshape_offset(0);
  PointJacobian all, without;
  int shape_entries = 0;
  for (Index i = 0; i < model.num_vertices(); ++i) {
    e.vertex_jacobian(i, all);
    e.vertex_jacobian(i, without, false);
    size_t kept = 0;
    for (size_t k = 0; k < all.params.size(); ++k) {
      if (all.params[k] >= first_shape) {
        ++shape_entries;
        continue;
      }
      ASSERT_LT(kept, without.params.size());
      EXPECT_EQ(without.params[kept], all.params[k]);
      EXPECT_EQ(without.columns[kept], all.columns[k]);  // the same bits
      ++kept;
    }
    EXPECT_EQ(kept, without.params.size()) << "vertex " << i;
  }
  EXPECT_GT(shape_entries, 0) << "the toy model's blendshapes should move some vertices";
}

TEST_F(PoseEvaluatorTest, SurfacePointJacobianMatchesFiniteDifferences) {
  std::vector<SurfacePoint> pts;
  for (const auto& l : model.landmarks) pts.push_back(l.point);
  for (const auto& d : model.drawings) pts.insert(pts.end(), d.points.begin(), d.points.end());
  for (std::uint64_t seed : {21u, 22u}) {
    const PoseParams p = test::random_toy_pose(model, seed);
    const Eigen::MatrixXd N = finite_difference(model, p, [&pts](const PoseEvaluator& e) {
      Eigen::VectorXd out(3 * pts.size());
      for (size_t k = 0; k < pts.size(); ++k) out.segment<3>(3 * k) = e.surface_point(pts[k]);
      return out;
    });
    PoseEvaluator e(model);
    e.set_params(p);
    const int P = e.layout().num_params();
    Eigen::MatrixXd A(3 * pts.size(), P);
    PointJacobian J;
    for (size_t k = 0; k < pts.size(); ++k) {
      e.surface_point_jacobian(pts[k], J);
      A.middleRows(3 * k, 3) = dense(J, P);
      EXPECT_LT((e.surface_point(pts[k]) - pts[k].position(e.vertices(), model.rest.F)).norm(), 1e-12);
    }
    EXPECT_LT(max_relative_error(A, N), 1e-6) << "seed " << seed;
  }
}

TEST_F(PoseEvaluatorTest, PivotJacobianMatchesFiniteDifferences) {
  const PoseParams p = test::random_toy_pose(model, 31);
  const int nb = model.num_bones();
  const Eigen::MatrixXd N = finite_difference(model, p, [nb](const PoseEvaluator& e) {
    Eigen::VectorXd out(3 * nb * nb);
    for (int j = 0; j < nb; ++j)
      for (int by = 0; by < nb; ++by) out.segment<3>(3 * (j * nb + by)) = e.pivot_moved_by(j, by);
    return out;
  });
  PoseEvaluator e(model);
  e.set_params(p);
  const int P = e.layout().num_params();
  Eigen::MatrixXd A(3 * nb * nb, P);
  PointJacobian J;
  for (int j = 0; j < nb; ++j)
    for (int by = 0; by < nb; ++by) {
      e.pivot_moved_by_jacobian(j, by, J);
      EXPECT_EQ(J.params.size(), 16u);
      A.middleRows(3 * (j * nb + by), 3) = dense(J, P);
    }
  EXPECT_LT(max_relative_error(A, N), 1e-6);
}

TEST_F(PoseEvaluatorTest, PivotMovedByOwnBoneIsTranslatedPivot) {
  PoseParams p = test::random_toy_pose(model, 41);
  PoseEvaluator e(model);
  e.set_params(p);
  for (int j = 0; j < model.num_bones(); ++j) {
    const Vec3 expected = p.global.apply(model.bones[j].pivot + p.bones[j].translation);
    EXPECT_LT((e.pivot_moved_by(j, j) - expected).norm(), 1e-9);
  }
  // At rest a child's pivot moved by its parent is the pivot itself (joint continuity holds).
  e.set_params(PoseParams::identity(model));
  EXPECT_LT((e.pivot_moved_by(2, 1) - model.bones[2].pivot).norm(), 1e-10);
  EXPECT_THROW(e.pivot_moved_by(0, 7), InvalidInput);
}

TEST_F(PoseEvaluatorTest, NormalsPointOutwardAtRest) {
  PoseEvaluator e(model);
  const Points N = e.vertex_normals();
  for (Index i = 0; i < model.num_vertices(); ++i) {
    EXPECT_NEAR(N.row(i).norm(), 1.0, 1e-12);
    const Vec3 v = model.rest.V.row(i).transpose();
    const Vec3 out = Vec3(v.x(), v.y(), 0.0).norm() > 1e-9 ? Vec3(v.x(), v.y(), 0.0) : Vec3(0, 0, v.z() - 120.0);
    EXPECT_GT(N.row(i).dot(out.transpose()), 0.0) << "vertex " << i;
  }
}

TEST_F(PoseEvaluatorTest, SettingParamsAgainKeepsThePoseAndAnyChangeReposes) {
  const PoseParams a = test::random_toy_pose(model, 4);
  PoseEvaluator e(model);
  e.set_params(a);
  const Points posed_a = e.vertices();
  e.set_params(a);  // the same bits: the pose is kept
  EXPECT_EQ(e.vertices(), posed_a);
  // A change of any kind of parameter gives the pose of the new parameters.
  std::vector<PoseParams> changed(5, a);
  changed[0].alpha[changed[0].alpha.size() - 1] += 0.5;
  changed[1].global.scale *= 1.01;
  changed[2].bones.back().translation.x() += 3.0;
  changed[3].bones.front().scale.z() *= 1.1;
  changed[4].global.rotation = Quat(Eigen::AngleAxisd(0.2, Vec3::UnitX())) * a.global.rotation;
  for (size_t k = 0; k < changed.size(); ++k) {
    e.set_params(changed[k]);
    EXPECT_EQ(e.vertices(), pose_vertices(model, changed[k])) << "change " << k;
    EXPECT_GT((e.vertices() - posed_a).cwiseAbs().maxCoeff(), 1e-6) << "change " << k;
    e.set_params(a);
    EXPECT_EQ(e.vertices(), posed_a) << "back from change " << k;
  }
}

// pose_rows writes the rows asked for, the same bits as set_params, and leaves the others and the
// evaluator as they were.
TEST_F(PoseEvaluatorTest, PosingSomeRowsGivesTheBitsOfTheWholePose) {
  PoseEvaluator e(model);
  const PoseParams at = test::random_toy_pose(model, 5);
  e.set_params(at);
  const Points before = e.vertices();
  for (unsigned seed : {6u, 7u, 8u}) {
    const PoseParams p = test::random_toy_pose(model, seed);
    std::vector<Index> rows;
    for (Index i = seed % 3; i < model.num_vertices(); i += 3) rows.push_back(i);
    Points out = before;
    e.pose_rows(p, rows, out);
    EXPECT_EQ(e.vertices(), before);
    const Points whole = pose_vertices(model, p);
    for (Index i = 0; i < model.num_vertices(); ++i)
      EXPECT_EQ(out.row(i), (i % 3 == seed % 3 ? whole : before).row(i)) << "vertex " << i;
  }
  Points short_rows(2, 3);
  EXPECT_THROW(e.pose_rows(at, {0}, short_rows), InvalidInput);
}

// The same on the default template (its blendshapes and skin weights), every vertex, from
// parameter sets one Newton-like increment away from each other, as the leave-one-out predictions.
TEST(PoseEvaluatorDefaultTemplate, PosingSomeRowsGivesTheBitsOfTheWholePose) {
  const RiggedModel& m = *test::default_template();
  PoseEvaluator e(m);
  std::vector<Index> all(static_cast<size_t>(m.num_vertices()));
  for (Index i = 0; i < m.num_vertices(); ++i) all[static_cast<size_t>(i)] = i;
  PoseParams p = PoseParams::identity(m);
  for (int k = 0; k < 3; ++k) {
    const Eigen::VectorXd delta = 0.05 * Eigen::VectorXd::Random(e.layout().num_params());
    e.layout().apply_increment(m, delta, p);
    Points out = Points::Zero(m.num_vertices(), 3);
    e.pose_rows(p, all, out);
    e.set_params(p);
    EXPECT_EQ(out, e.vertices()) << "set " << k;
  }
}

TEST_F(PoseEvaluatorTest, RejectsMismatchedParams) {
  PoseEvaluator e(model);
  PoseParams p = PoseParams::identity(model);
  p.alpha.resize(2);
  EXPECT_THROW(e.set_params(p), InvalidInput);
  p = PoseParams::identity(model);
  p.bones.pop_back();
  EXPECT_THROW(e.set_params(p), InvalidInput);
}

}  // namespace
}  // namespace breastfit::model
