#include "breastfit/fit/problem.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "breastfit/fit/priors.h"
#include "breastfit/fit/sliding_landmarks.h"
#include "breastfit/fit/surface_term.h"
#include "breastfit/mesh/normals.h"

namespace breastfit::fit {

Problem::Problem(const model::RiggedModel& model, ScanTarget& scan, const FitOptions& options,
                 const std::vector<LandmarkTarget>& landmarks)
    : model_(model), scan_(scan), options_(options), landmarks_(landmarks), ev_(model) {}

void Problem::update_correspondences(double max_dist, int stride, bool with_reverse) {
  const Points N = mesh::vertex_normals(ev_.vertices(), model_.rest.F);
  pairs_ = find_correspondences(ev_.vertices(), N, scan_, options_.correspondences, max_dist, stride, &stats_,
                                &hints_);
  reverse_pairs_.clear();
  reverse_stats_ = CorrespondenceStats{};
  if (with_reverse)
    reverse_pairs_ = find_reverse_correspondences(ev_.vertices(), model_.rest.F, scan_, options_.correspondences,
                                                  max_dist, &reverse_stats_, &reverse_hints_);
}

void Problem::update_sliding_landmarks() {
  const Vec3 up = posed_vertical_axis(model_, ev_.params());
  for (auto& t : landmarks_)
    if (const auto region = sliding_landmark_region(t.name))
      t.sliding_point = lowest_region_point(model_, ev_.vertices(), up, *region);
}

void Problem::clear_correspondences() {
  pairs_.clear();
  reverse_pairs_.clear();
  stats_ = CorrespondenceStats{};
  reverse_stats_ = CorrespondenceStats{};
}

EnergyBreakdown Problem::evaluate(NormalEquations* eq) const {
  const auto& w = options_.weights;
  EnergyBreakdown e;
  const double data_scale = 1.0 / (w.lambda_data * std::max<size_t>(1, pairs_.size()));
  e.data = add_data_term(ev_, pairs_, options_.correspondences.point_to_point_weight, data_scale, eq);
  if (!reverse_pairs_.empty())
    e.reverse = add_reverse_term(ev_, reverse_pairs_, 1.0 / (w.lambda_reverse * reverse_pairs_.size()), eq);
  e.landmarks = add_landmark_term(ev_, landmarks_, 1.0 / w.lambda_landmarks, eq);
  PriorScales ps;
  ps.scale = 1.0 / w.lambda_scale;
  ps.blendshape = 1.0 / w.lambda_blendshapes;
  ps.joint = 1.0 / w.lambda_joints;
  ps.continuity = 1.0 / w.lambda_continuity;
  ps.joint_translation_scale_mm = w.joint_translation_scale_mm;
  const PriorCosts pc = add_priors(ev_, ps, eq);
  e.scale = pc.scale;
  e.blendshapes = pc.blendshape;
  e.joints = pc.joint;
  e.continuity = pc.continuity;
  return e;
}

void Problem::orient_scan_normals(double max_dist) {
  const Points N = mesh::vertex_normals(ev_.vertices(), model_.rest.F);
  const Points& V = ev_.vertices();
  double agree = 0, disagree = 0;
  for (Index i = 0; i < V.rows(); i += 4) {
    const auto m = scan_.match(V.row(i).transpose(), max_dist);
    if (!m || m->on_boundary) continue;
    const double d = N.row(i).dot(m->normal);
    (d >= 0 ? agree : disagree) += std::abs(d);
  }
  if (disagree > agree) scan_.set_normal_sign(-scan_.normal_sign());
}

double Problem::kept_mae_mm() const {
  if (pairs_.empty()) return std::numeric_limits<double>::infinity();
  double sum = 0;
  for (const auto& c : pairs_) sum += std::abs(c.normal.dot(ev_.vertices().row(c.vertex).transpose() - c.target));
  return sum / pairs_.size();
}

}  // namespace breastfit::fit
