#include "breastfit/fit/initialization.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "breastfit/core/errors.h"
#include "breastfit/fit/parallel_chunks.h"
#include "breastfit/mesh/landmark_names.h"
#include "breastfit/model/pose_evaluator.h"
#include "breastfit/spatial/closest_point_index.h"

namespace breastfit::fit {
namespace {

Points model_landmarks_at_rest(const model::RiggedModel& model, const std::vector<LandmarkTarget>& targets) {
  Points P(targets.size(), 3);
  for (size_t i = 0; i < targets.size(); ++i)
    P.row(i) = model.landmarks[targets[i].model_landmark].point.position(model.rest.V, model.rest.F).transpose();
  return P;
}

Points target_positions(const std::vector<LandmarkTarget>& targets) {
  Points P(targets.size(), 3);
  for (size_t i = 0; i < targets.size(); ++i) P.row(i) = targets[i].position.transpose();
  return P;
}

double rms_after(const model::Similarity& s, const Points& src, const Points& dst) {
  double sum = 0;
  for (Index i = 0; i < src.rows(); ++i) sum += (s.apply(src.row(i).transpose()) - dst.row(i).transpose()).squaredNorm();
  return std::sqrt(sum / std::max<Index>(1, src.rows()));
}

// Principal axes (columns, by decreasing variance) and centroid of points.
void principal_axes(const Points& P, Vec3& centroid, Mat3& axes, Vec3& variances) {
  centroid = P.colwise().mean().transpose();
  const Points C = P.rowwise() - centroid.transpose();
  const Mat3 cov = (C.transpose() * C) / std::max<Index>(1, P.rows());
  Eigen::SelfAdjointEigenSolver<Mat3> es(cov);
  for (int k = 0; k < 3; ++k) {
    axes.col(k) = es.eigenvectors().col(2 - k);
    variances[k] = es.eigenvalues()[2 - k];
  }
}

}  // namespace

model::Similarity umeyama_similarity(const Points& src, const Points& dst) {
  if (src.rows() < 3 || src.rows() != dst.rows())
    throw InvalidInput("a similarity needs at least 3 matching points (got " + std::to_string(src.rows()) + ")");
  Vec3 c;
  Mat3 axes;
  Vec3 var;
  principal_axes(src, c, axes, var);
  if (var[1] < 1e-6 * std::max(var[0], 1e-300))
    throw InvalidInput("the landmarks are collinear: their similarity transform is undefined");
  const Eigen::Matrix<double, 3, Eigen::Dynamic> S = src.transpose();
  const Eigen::Matrix<double, 3, Eigen::Dynamic> D = dst.transpose();
  const Eigen::Matrix4d T = Eigen::umeyama(S, D, true);
  model::Similarity sim;
  const Mat3 sR = T.topLeftCorner<3, 3>();
  sim.scale = std::cbrt(sR.determinant());
  sim.rotation = Quat(sR / sim.scale).normalized();
  sim.translation = T.topRightCorner<3, 1>();
  return sim;
}

LandmarkInitialization initialize_from_landmarks(const model::RiggedModel& model,
                                                 std::vector<LandmarkTarget>& targets) {
  LandmarkInitialization out;
  const Points src = model_landmarks_at_rest(model, targets);
  const Points dst = target_positions(targets);
  out.similarity = umeyama_similarity(src, dst);
  out.rms_mm = rms_after(out.similarity, src, dst);

  // Same positions with every _R/_L label exchanged.
  std::vector<LandmarkTarget> swapped = targets;
  bool any_sided = false;
  for (auto& t : swapped) {
    const std::string other = mirrored_landmark_name(t.name);
    if (other == t.name) continue;
    const auto idx = model.landmark_index(other);
    if (!idx) continue;
    any_sided = true;
    t.name = other;
    t.model_landmark = *idx;
  }
  if (!any_sided) return out;
  const Points src_swapped = model_landmarks_at_rest(model, swapped);
  const model::Similarity sim_swapped = umeyama_similarity(src_swapped, dst);
  const double rms_swapped = rms_after(sim_swapped, src_swapped, dst);
  out.swapped_rms_mm = rms_swapped;
  if (rms_swapped < 0.6 * out.rms_mm && out.rms_mm > 15.0) {
    out.swapped = true;
    out.swapped_rms_mm = out.rms_mm;  // as given
    out.rms_mm = rms_swapped;
    out.similarity = sim_swapped;
    targets = swapped;
  }
  return out;
}

std::array<double, 2> initialize_arms(const model::RiggedModel& model, const ScanTarget& scan,
                                      model::PoseParams& params, bool two_way, int threads) {
  constexpr double kMissMm = 40.0;  // score of a vertex with nothing on the scan within this distance
  std::array<double, 2> raised{0.0, 0.0};
  // Poses only the vertices an angle's score reads (pose_rows: the bits set_params gives them),
  // shared by the chunks (pose_rows does not change it).
  const model::PoseEvaluator evaluator(model);
  std::vector<int> angles_deg;
  for (int deg = -40; deg <= 90; deg += 10) angles_deg.push_back(deg);
  for (const char* name : {"upper_arm_R", "upper_arm_L"}) {
    const auto bone = model.bone_index(name);
    if (!bone) continue;
    const std::vector<Index> arm = model.vertices_mostly_moved_by(*bone);
    if (arm.size() < 10) continue;
    // Two-way: the scan's samples beyond this shoulder (body frame: lateral of the joint, not far
    // below it) must lie near the arm too, so that an arm lowered onto the chest wall, which lies
    // on the scan as well, does not win.
    std::vector<Vec3> zone;
    if (two_way) {
      const Vec3 pivot = model.bones[*bone].pivot;
      const model::Similarity to_body = params.global.inverse();
      const Points& S = scan.sample_points();
      for (Index i = 0; i < S.rows(); ++i) {
        const Vec3 b = to_body.apply(S.row(i).transpose());
        if (b.x() * pivot.x() > pivot.x() * pivot.x() && b.z() > pivot.z() - 350.0) zone.push_back(S.row(i).transpose());
      }
    }
    const Quat base = params.bones[*bone].rotation;
    // Positive angles raise the arm: about −y for the left arm (the template's x points to the
    // left, z up: a turn about +y takes +x towards −z, down), about +y for the right.
    const double sign = std::string(name).back() == 'L' ? -1.0 : 1.0;
    std::vector<Quat> rotations;
    for (int deg : angles_deg)
      rotations.push_back(Quat(Eigen::AngleAxisd(sign * deg * M_PI / 180.0, Vec3::UnitY())) * base);
    // Every angle scored on its own, the best chosen in order. The angles run in chunks (in
    // parallel) of kAnglesPerChunk, each search warm-started from the vertex's face at the chunk's
    // previous angle (the same answers; only faster). An angle reads every second arm vertex.
    constexpr Index kAnglesPerChunk = 7;
    std::vector<Index> read;
    for (size_t k = 0; k < arm.size(); k += 2) read.push_back(arm[k]);
    std::vector<double> scores(rotations.size(), 0.0);
    for_each_chunk(static_cast<Index>(rotations.size()), kAnglesPerChunk, threads, [&](Index, Index begin, Index end) {
      Points V(model.num_vertices(), 3);  // the rows of `read` posed at each angle
      model::PoseParams trial = params;
      std::vector<Index> hints(arm.size(), -1);
      // The searched vertices (every second one of the arm), searched along a Morton curve over
      // their positions (nearby queries find the scan index's nodes in the cache), each distance in
      // its own slot and summed in the vertices' order: the same score as searching in order.
      const size_t searched = (arm.size() + 1) / 2;
      Points Q(static_cast<Index>(searched), 3);
      std::vector<double> distance(searched);
      for (Index a = begin; a < end; ++a) {
        trial.bones[*bone].rotation = rotations[static_cast<size_t>(a)];
        evaluator.pose_rows(trial, read, V);
        for (size_t s = 0; s < searched; ++s) Q.row(static_cast<Index>(s)) = V.row(arm[2 * s]);
        for (const std::uint32_t s : spatial::query_order(Q)) {
          const auto m = scan.match(Q.row(static_cast<Index>(s)).transpose(), kMissMm, &hints[2 * s]);
          distance[s] = m ? std::sqrt(m->sq_dist) : kMissMm;
        }
        double score = 0;
        for (size_t s = 0; s < searched; ++s) score += distance[s];
        if (!zone.empty()) {
          score /= static_cast<double>((arm.size() + 1) / 2);
          double reverse = 0;
          for (const Vec3& z : zone) {
            double nearest = kMissMm * kMissMm;
            for (size_t k = 0; k < arm.size(); k += 2) nearest = std::min(nearest, (V.row(arm[k]).transpose() - z).squaredNorm());
            reverse += std::sqrt(nearest);
          }
          score += reverse / static_cast<double>(zone.size());
        }
        scores[static_cast<size_t>(a)] = score;
      }
    });
    double best_score = std::numeric_limits<double>::infinity();
    Quat best = base;
    int best_deg = 0;
    for (size_t a = 0; a < rotations.size(); ++a) {
      if (scores[a] < best_score - 1e-9) {
        best_score = scores[a];
        best = rotations[a];
        best_deg = angles_deg[a];
      }
    }
    params.bones[*bone].rotation = best;
    raised[std::string(name).back() == 'L' ? 1 : 0] = best_deg;
  }
  return raised;
}

}  // namespace breastfit::fit
