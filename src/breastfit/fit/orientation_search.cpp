#include "breastfit/fit/orientation_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "breastfit/fit/initialization.h"
#include "breastfit/fit/problem.h"
#include "breastfit/fit/stage_minimizer.h"
#include "breastfit/mesh/body_frame.h"
#include "breastfit/mesh/normals.h"

namespace breastfit::fit {
namespace {

constexpr double kTemplateRestAbductionDeg = 24.0;  // docs/TEMPLATE.md: arms at rest
constexpr double kDistinctDeg = 45.0;   // hypotheses closer than this are one orientation
constexpr int kRefined = 3;             // distinct hypotheses that get the arms and a pose fit
constexpr double kScoreDistanceMm = 25.0;  // pairs farther than this count as misses
constexpr double kMissPenaltyMm = 25.0;    // a miss costs as much as a pair this far

struct Turn {
  const char* name;
  Mat3 rotation;  // in the body frame (x left, y posterior, z superior)
};

Mat3 about(const Vec3& axis, double deg) { return Eigen::AngleAxisd(deg * M_PI / 180.0, axis).toRotationMatrix(); }

// The dihedral group of the antero-posterior axis: the long axis up or down or lying across, seen
// from the front or from behind (the shape's AP axis is the reliable one, its signs and the
// in-plane axes are not).
std::vector<Turn> turns() {
  const Vec3 x = Vec3::UnitX(), y = Vec3::UnitY(), z = Vec3::UnitZ();
  return {{"as found", Mat3::Identity()},
          {"from behind", about(z, 180)},
          {"upside down", about(y, 180)},
          {"upside down, from behind", about(x, 180)},
          {"long axis across (+90 deg)", about(y, 90)},
          {"long axis across (-90 deg)", about(y, -90)},
          {"long axis across (+90 deg), from behind", about(z, 180) * about(y, 90)},
          {"long axis across (-90 deg), from behind", about(z, 180) * about(y, -90)}};
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// Template → scan for a body-frame rotation R (template body frame → world): the template's
// front-facing part centred on the scan across, its most anterior points on the scan's.
model::Similarity place(const model::RiggedModel& model, const Points& front, const Points& scan_points,
                        const Mat3& R) {
  model::Similarity s;
  s.rotation = Quat(R).normalized();
  s.scale = 1.0;  // the units are known: a template-sized torso
  const Vec3 c_scan = scan_points.colwise().mean().transpose();
  const Vec3 c_front = front.colwise().mean().transpose();
  s.translation = c_scan - R * c_front;
  const Vec3 anterior = -R.col(1);
  std::vector<double> a_scan, a_model;
  for (Index i = 0; i < scan_points.rows(); ++i) a_scan.push_back(anterior.dot(scan_points.row(i).transpose()));
  for (Index i = 0; i < model.rest.V.rows(); ++i) a_model.push_back(anterior.dot(s.apply(model.rest.V.row(i).transpose())));
  s.translation += (quantile(a_scan, 0.98) - quantile(a_model, 0.98)) * anterior;
  return s;
}

// Two-way score at the problem's current parameters (see OrientationHypothesis).
void score(Problem& problem, const model::RiggedModel& model, OrientationHypothesis& h) {
  problem.update_correspondences(kScoreDistanceMm, 2, true);
  const auto& fs = problem.stats();
  h.forward_kept = fs.candidates ? static_cast<double>(fs.kept) / fs.candidates : 0.0;
  h.forward_mae_mm = problem.pairs().empty() ? kScoreDistanceMm : problem.kept_mae_mm();
  const Points& V = problem.evaluator().vertices();
  double sum = 0;
  for (const auto& r : problem.reverse_pairs())
    sum += std::abs(r.normal.dot(r.source - r.model_point.position(V, model.rest.F)));
  const auto& rs = problem.reverse_stats();
  h.reverse_kept = rs.candidates ? static_cast<double>(rs.kept) / rs.candidates : 0.0;
  h.reverse_mae_mm = problem.reverse_pairs().empty() ? kScoreDistanceMm : sum / problem.reverse_pairs().size();
  h.score = h.forward_mae_mm + h.reverse_mae_mm + kMissPenaltyMm * ((1.0 - h.forward_kept) + (1.0 - h.reverse_kept));
}

// Lying on the back, the breasts fall sideways and towards the head and flatten: the fit starts
// them there (mid-range of the template's supine displacement shapes), so the surface does not
// hold them where a standing breast would be.
void start_breasts_supine(const model::RiggedModel& model, model::PoseParams& params) {
  for (int k = 0; k < model.num_blendshapes(); ++k) {
    const auto& b = model.blendshapes[static_cast<size_t>(k)];
    const std::string& n = b.name;
    double w;
    if (n.rfind("breast_lateral", 0) == 0 || n.find("supine") != std::string::npos)
      w = 0.8 * b.hi;
    else if (n.rfind("breast_cranial", 0) == 0)
      w = 0.5 * b.hi;
    else if (n.rfind("breast_ptosis", 0) == 0 || n.rfind("breast_projection", 0) == 0)
      w = 0.75 * b.lo;
    else
      continue;
    params.alpha[k] = std::clamp(w, b.lo, b.hi);
  }
}

}  // namespace

double rotation_angle_deg(const Quat& a, const Quat& b) { return a.angularDistance(b) * 180.0 / M_PI; }

OrientationSearch search_orientation(const model::RiggedModel& model, ScanTarget& scan, const FitOptions& options) {
  OrientationSearch out;
  const mesh::BodyFrame frame = mesh::body_frame_from_principal_axes(scan.mesh());
  out.body_frame = frame.description;
  const Mat3 B = frame.body_to_world.topLeftCorner<3, 3>();

  // The template's anterior-facing vertices (a scan sees the front).
  Points front;
  {
    std::vector<Index> idx;
    const Points N = mesh::vertex_normals(model.rest.V, model.rest.F);
    for (Index i = 0; i < model.rest.V.rows(); ++i)
      if (N(i, 1) < -0.3) idx.push_back(i);
    front.resize(static_cast<Index>(idx.size()), 3);
    for (size_t k = 0; k < idx.size(); ++k) front.row(static_cast<Index>(k)) = model.rest.V.row(idx[k]);
  }
  const Points& scan_points = scan.sample_points().rows() >= 10 ? scan.sample_points() : scan.mesh().V;

  FitOptions quick = options;
  quick.correspondences.max_distance_start_mm = std::max(80.0, options.correspondences.max_distance_start_mm);
  quick.correspondences.max_distance_end_mm = kScoreDistanceMm;
  quick.correspondences.reverse_samples = 0;
  const StageOptions rigid{"orientation_rigid", true, false, false, 8, 8};
  StageOptions pose = options.pose;
  pose.name = "orientation_pose";
  pose.max_iterations = 5;
  pose.vertex_stride = 4;
  Problem problem(model, scan, quick, {});

  // 1. Every turn: placed, then a short rigid+scale ICP, scored.
  std::vector<model::PoseParams> fitted;
  for (const Turn& turn : turns()) {
    OrientationHypothesis h;
    h.name = turn.name;
    model::PoseParams params = model::PoseParams::identity(model);
    params.global = place(model, front, scan_points, B * turn.rotation);
    problem.evaluator().set_params(params);
    problem.orient_scan_normals(quick.correspondences.max_distance_start_mm);
    FitSummary ignored;
    if (minimize_stages(problem, {rigid}, params, ignored) == Termination::NumericalFailure) continue;
    problem.evaluator().set_params(params);
    score(problem, model, h);
    h.similarity = params.global;
    out.hypotheses.push_back(h);
    fitted.push_back(params);
  }
  if (out.hypotheses.empty()) {  // every start failed numerically: the shape's frame as it is
    out.params = model::PoseParams::identity(model);
    out.params.global = place(model, front, scan_points, B);
    return out;
  }

  // 2. The best few distinct orientations: arms, a brief pose fit, scored again.
  std::vector<size_t> order(out.hypotheses.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto by_score = [&](size_t a, size_t b) {
    return out.hypotheses[a].score < out.hypotheses[b].score ||
           (out.hypotheses[a].score == out.hypotheses[b].score && a < b);
  };
  std::stable_sort(order.begin(), order.end(), by_score);
  std::vector<size_t> chosen;
  for (size_t i : order) {
    if (static_cast<int>(chosen.size()) == kRefined) break;
    bool distinct = true;
    for (size_t j : chosen)
      distinct = distinct && rotation_angle_deg(out.hypotheses[i].similarity.rotation,
                                                out.hypotheses[j].similarity.rotation) >= kDistinctDeg;
    if (distinct) chosen.push_back(i);
  }
  std::vector<std::array<double, 2>> raised(out.hypotheses.size(), {0.0, 0.0});
  for (size_t i : chosen) {
    model::PoseParams& params = fitted[i];
    problem.evaluator().set_params(params);
    problem.orient_scan_normals(quick.correspondences.max_distance_end_mm);
    raised[i] = initialize_arms(model, scan, params, true, options.threads);
    FitSummary ignored;
    if (minimize_stages(problem, {pose}, params, ignored) == Termination::NumericalFailure) continue;
    problem.evaluator().set_params(params);
    score(problem, model, out.hypotheses[i]);
    out.hypotheses[i].similarity = params.global;
    out.hypotheses[i].refined = true;
  }
  // Refined hypotheses first (their scores are comparable), then by score.
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if (out.hypotheses[a].refined != out.hypotheses[b].refined) return out.hypotheses[a].refined;
    return by_score(a, b);
  });
  const size_t best = order.front();
  out.params = fitted[best];
  for (int k = 0; k < 2; ++k) out.arm_abduction_deg[k] = kTemplateRestAbductionDeg + raised[best][k];
  // Standing, the arms hang beside the trunk; supine, they lie out on arm boards: the scan is
  // then much wider than high (body frame of the kept hypothesis; 1.04-1.19 standing, 1.21-1.42
  // supine on 30 generated scans).
  std::vector<double> across, along;
  const model::Similarity to_body = out.params.global.inverse();
  for (Index i = 0; i < scan_points.rows(); ++i) {
    const Vec3 b = to_body.apply(scan_points.row(i).transpose());
    across.push_back(b.x());
    along.push_back(b.z());
  }
  const double height = quantile(along, 0.99) - quantile(along, 0.01);
  out.width_to_height = height > 0 ? (quantile(across, 0.99) - quantile(across, 0.01)) / height : 0.0;
  const bool supine = out.width_to_height >= 1.2;
  out.arm_pose = supine ? "arms abducted (supine, arm boards)" : "arms hanging (standing)";
  if (supine) start_breasts_supine(model, out.params);
  for (size_t i : order) {
    if (i == best || !out.hypotheses[i].refined) continue;
    if (rotation_angle_deg(out.hypotheses[i].similarity.rotation, out.hypotheses[best].similarity.rotation) <
        kDistinctDeg)
      continue;
    const double b = std::max(out.hypotheses[best].score, 1e-9);
    out.margin = std::max(0.0, (out.hypotheses[i].score - b) / b);
    out.runner_up = out.hypotheses[i].name;
    break;
  }
  if (out.runner_up.empty()) out.margin = std::numeric_limits<double>::infinity();
  std::vector<OrientationHypothesis> sorted;
  for (size_t i : order) sorted.push_back(out.hypotheses[i]);
  out.hypotheses = std::move(sorted);
  // The scan's normal sign as the best hypothesis sees it.
  problem.evaluator().set_params(out.params);
  problem.orient_scan_normals(quick.correspondences.max_distance_end_mm);
  return out;
}

}  // namespace breastfit::fit
