// The model → scan pairs: searched in any order (along a Morton curve over the queries, on any
// number of threads), they are those of a search vertex by vertex.
#include "breastfit/fit/correspondences.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "breastfit/core/rng.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/mesh/normals.h"
#include "spatial/spatial_test_meshes.h"

namespace breastfit::fit {
namespace {

namespace meshes = breastfit::test::spatial_meshes;

// The definition, vertex by vertex in order.
std::vector<Correspondence> reference(const Points& V, const Points& N, const ScanTarget& scan,
                                      const CorrespondenceOptions& o, double max_distance_mm, int stride,
                                      CorrespondenceStats& st) {
  const double cos_limit = std::cos(o.max_normal_angle_deg * M_PI / 180.0);
  std::vector<Correspondence> out;
  st = CorrespondenceStats{};
  st.max_distance_mm = max_distance_mm;
  for (Index i = 0; i < V.rows(); i += stride) {
    ++st.candidates;
    const Vec3 q = V.row(i).transpose();
    const auto m = scan.match(q, max_distance_mm);
    if (!m) {
      ++st.rejected_distance;
    } else if (o.reject_boundary && m->on_boundary) {
      ++st.rejected_boundary;
    } else if (N.row(i).dot(m->normal.transpose()) < cos_limit) {
      ++st.rejected_normal;
    } else {
      Correspondence c;
      c.vertex = i;
      c.target = m->point;
      c.normal = m->normal;
      const double r = std::sqrt((1.0 - o.point_to_point_weight) * std::pow(c.normal.dot(q - c.target), 2) +
                                 o.point_to_point_weight * (q - c.target).squaredNorm());
      c.weight = robust_weight(o.kernel, r, o.kernel_scale_mm);
      out.push_back(c);
      ++st.kept;
    }
  }
  return out;
}

TEST(FindCorrespondences, TheSamePairsAsAVertexByVertexSearch) {
  // The scan: a sheet with holes and an open border. The model: a coarser noisy sheet above it,
  // its vertices in a shuffled order (so the Morton order differs from the vertex order), some
  // normals flipped and some vertices far away.
  const ScanTarget scan(meshes::noisy_sheet(60, 2.0, 0.3, 0.05, 31), 0);
  TriangleMesh model = meshes::noisy_sheet(25, 5.0, 0.5, 0.0, 32);
  Rng rng(33);
  const Index nv = model.num_vertices();
  Points V(nv, 3);
  for (Index i = 0; i < nv; ++i) {
    const Index j = static_cast<Index>(rng.below(static_cast<std::uint64_t>(nv - i))) + i;
    model.V.row(i).swap(model.V.row(j));
    V.row(i) = model.V.row(i) + Eigen::RowVector3d(0, 0, rng.uniform(-6.0, 6.0));
  }
  Points N = Points::Zero(nv, 3);
  for (Index i = 0; i < nv; ++i) N(i, 2) = rng.uniform() < 0.1 ? -1.0 : 1.0;
  for (Index i = 0; i < nv; i += 17) V(i, 2) += 50.0;
  CorrespondenceOptions o;
  for (const int stride : {1, 3}) {
    CorrespondenceStats expected_stats;
    const std::vector<Correspondence> expected = reference(V, N, scan, o, 5.0, stride, expected_stats);
    ASSERT_GT(expected_stats.kept, 50);
    EXPECT_GT(expected_stats.rejected_distance, 0);
    EXPECT_GT(expected_stats.rejected_normal, 0);
    EXPECT_GT(expected_stats.rejected_boundary, 0);
    std::vector<Index> hints;
    for (const int threads : {1, 2, 3, 1}) {  // the last run warm-started by the ones before
      CorrespondenceStats st;
      const std::vector<Correspondence> got = find_correspondences(V, N, scan, o, 5.0, stride, &st, &hints, threads);
      ASSERT_EQ(got.size(), expected.size()) << "stride " << stride << ", threads " << threads;
      for (size_t k = 0; k < got.size(); ++k) {
        EXPECT_EQ(got[k].vertex, expected[k].vertex);
        EXPECT_EQ(got[k].target, expected[k].target);
        EXPECT_EQ(got[k].normal, expected[k].normal);
        EXPECT_EQ(got[k].weight, expected[k].weight);
      }
      EXPECT_EQ(st.candidates, expected_stats.candidates);
      EXPECT_EQ(st.kept, expected_stats.kept);
      EXPECT_EQ(st.rejected_distance, expected_stats.rejected_distance);
      EXPECT_EQ(st.rejected_boundary, expected_stats.rejected_boundary);
      EXPECT_EQ(st.rejected_normal, expected_stats.rejected_normal);
      EXPECT_EQ(st.max_distance_mm, 5.0);
    }
  }
}

}  // namespace
}  // namespace breastfit::fit
