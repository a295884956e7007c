#include "breastfit/fit/problem.h"

#include <cmath>
#include <limits>
#include <utility>

#include "breastfit/core/errors.h"
#include "breastfit/fit/energy_terms.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/spatial/closest_point_index.h"

namespace breastfit::fit {

Problem::Problem(const model::RiggedModel& model, ScanTarget& scan, const FitOptions& options,
                 std::vector<LandmarkTarget> landmarks)
    : model_(model), scan_(scan), options_(options), landmarks_(std::move(landmarks)), ev_(model) {
  for (const auto& spec : energy_terms()) {
    const double lambda = options.weights.lambda(spec.name);
    if (spec.can_disable && lambda <= 0) continue;
    terms_.push_back({std::string(spec.name), 1.0 / lambda, spec.make()});
  }
}

Problem::~Problem() = default;

TermContext Problem::context() const {
  return {ev_, found_.pairs, found_.reverse_pairs, landmarks_, options_, robust_landmarks_};
}

void Problem::update_correspondences(double max_dist, int stride, bool with_reverse) {
  const double sign = scan_.normal_sign();
  const auto& key = found_.key;
  if (key && key->max_distance_mm == max_dist && key->stride == stride && key->with_reverse == with_reverse &&
      key->normal_sign == sign && key->vertices == ev_.vertices())
    return;
  found_.key = CorrespondenceState::Key{ev_.vertices(), max_dist, sign, stride, with_reverse};
  const Points N = mesh::vertex_normals(ev_.vertices(), model_.rest.F);
  found_.pairs = find_correspondences(ev_.vertices(), N, scan_, options_.correspondences, max_dist, stride,
                                      &found_.stats, &found_.hints, options_.threads);
  found_.reverse_pairs.clear();
  found_.reverse_stats = CorrespondenceStats{};
  if (with_reverse) {
    if (posed_index_)
      posed_index_->move_vertices(ev_.vertices(), N);
    else {
      TriangleMesh posed;
      posed.V = ev_.vertices();
      posed.F = model_.rest.F;
      posed_index_ = std::make_unique<spatial::ClosestPointIndex>(std::move(posed));
    }
    found_.reverse_pairs = find_reverse_correspondences(*posed_index_, scan_, options_.correspondences, max_dist,
                                                        &found_.reverse_stats, &found_.reverse_hints, options_.threads);
  }
}

void Problem::clear_correspondences() {
  found_.key.reset();
  found_.pairs.clear();
  found_.reverse_pairs.clear();
  found_.stats = CorrespondenceStats{};
  found_.reverse_stats = CorrespondenceStats{};
}

void Problem::update_terms(bool robust_landmarks) {
  robust_landmarks_ = robust_landmarks;
  const TermContext ctx = context();
  for (auto& t : terms_) t.term->update(ctx);
}

EnergyBreakdown Problem::evaluate(NormalEquations* eq) const {
  const TermContext ctx = context();
  EnergyBreakdown e;
  e.terms.reserve(energy_terms().size());
  size_t next = 0;
  for (const auto& spec : energy_terms()) {  // disabled terms are listed with 0
    if (next < terms_.size() && terms_[next].name == spec.name) {
      e.terms.emplace_back(terms_[next].name, terms_[next].term->evaluate(ctx, terms_[next].weight, eq));
      ++next;
    } else {
      e.terms.emplace_back(std::string(spec.name), 0.0);
    }
  }
  return e;
}

double Problem::evaluate_term(std::string_view name, NormalEquations* eq) const {
  for (const auto& t : terms_)
    if (t.name == name) return t.term->evaluate(context(), t.weight, eq);
  if (!find_energy_term(name))
    throw InvalidInput("'" + std::string(name) + "' is not an energy term (expected one of: " + energy_term_names() + ")");
  return 0.0;  // disabled
}

double Problem::evaluate_landmark(size_t i, NormalEquations* eq) const {
  std::vector<LandmarkTarget> one = landmarks_;  // the others at weight 0: the terms keep their per-landmark state
  for (size_t k = 0; k < one.size(); ++k)
    if (k != i) one[k].weight = 0.0;
  const TermContext ctx{ev_, found_.pairs, found_.reverse_pairs, one, options_, robust_landmarks_};
  double cost = 0.0;
  for (const auto& t : terms_)
    if (t.name == "landmarks" || t.name == "sliding_landmarks") cost += t.term->evaluate(ctx, t.weight, eq);
  return cost;
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
  const auto& pairs = found_.pairs;
  if (pairs.empty()) return std::numeric_limits<double>::infinity();
  double sum = 0;
  for (const auto& c : pairs) sum += std::abs(c.normal.dot(ev_.vertices().row(c.vertex).transpose() - c.target));
  return sum / pairs.size();
}

}  // namespace breastfit::fit
