#include "breastfit/fit/registration.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <set>

#include "breastfit/core/errors.h"
#include "breastfit/core/timer.h"
#include "breastfit/fit/bilateral_check.h"
#include "breastfit/fit/breast_fold.h"
#include "breastfit/fit/combined_check.h"
#include "breastfit/fit/hanging_acromion.h"
#include "breastfit/fit/hanging_breast_fold.h"
#include "breastfit/fit/hanging_midaxillary.h"
#include "breastfit/fit/initialization.h"
#include "breastfit/fit/jugular_notch.h"
#include "breastfit/fit/landmark_prediction.h"
#include "breastfit/fit/midline_notch_check.h"
#include "breastfit/fit/nipple_apex.h"
#include "breastfit/fit/nipple_apex_check.h"
#include "breastfit/fit/nipple_bump_check.h"
#include "breastfit/fit/orientation_search.h"
#include "breastfit/fit/parallel_chunks.h"
#include "breastfit/fit/pectoral_check.h"
#include "breastfit/fit/pectoral_insertion.h"
#include "breastfit/fit/stage_minimizer.h"
#include "breastfit/fit/problem.h"
#include "breastfit/fit/shoulder_landmarks.h"
#include "breastfit/fit/skin_around.h"
#include "breastfit/fit/sliding_landmarks.h"
#include "breastfit/fit/sternum_length.h"
#include "breastfit/fit/xiphoid_check.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/mesh/landmark_names.h"

namespace breastfit::fit {
namespace {

// A given landmark against its own anatomical definition found on the scan.
struct AnatomyCheck {
  double distance_mm = 0, tolerance_mm = 0;
  std::string what;
};

// The given landmarks against their predictions: where the anatomy and the other landmarks put
// them (empty when not checked), against their own anatomy on the scan (per landmark, when
// checked), and the factor each one's weight was multiplied by (< 1: flagged before the refit).
struct PlacedCheck {
  std::vector<Vec3> predicted;
  std::vector<std::optional<AnatomyCheck>> anatomy;
  std::vector<double> held_off;
  std::vector<bool> flagged;  // beyond a tolerance before the refit
};

std::string fmt(double v, int digits = 1) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace

std::vector<LandmarkTarget> match_landmarks(const model::RiggedModel& model,
                                            const std::vector<std::pair<std::string, Vec3>>& landmarks_mm) {
  std::vector<LandmarkTarget> out;
  std::set<std::string> seen;
  for (const auto& [name, pos] : landmarks_mm) {
    if (!seen.insert(name).second) throw InvalidInput("landmark '" + name + "' is given twice");
    if (!pos.allFinite()) throw InvalidInput("landmark '" + name + "' has a non-finite position");
    const auto idx = model.landmark_index(name);
    if (!idx)
      throw InvalidInput("landmark '" + name + "' is not a landmark of template '" + model.name +
                         "' (expected: " + landmark_name_list() + ")");
    out.push_back({name, *idx, pos, landmark_weight(name)});
  }
  // The paper's order (kLandmarkNames), so that "the first n landmarks" is reproducible.
  std::stable_sort(out.begin(), out.end(), [](const LandmarkTarget& a, const LandmarkTarget& b) {
    return landmark_index(a.name).value_or(99) < landmark_index(b.name).value_or(99);
  });
  return out;
}

namespace {

// The verdict on the final state: enough of the template on the scan, close enough.
Verdict judge(const FitOptions& options, const Problem& problem, Termination termination, double kept_mae_mm) {
  if (termination == Termination::NumericalFailure) return {false, "numerical failure: the energy became non-finite"};
  if (termination == Termination::Aborted) return {false, "aborted before the end of the registration"};
  const auto& st = problem.stats();
  const double kept_fraction = st.candidates > 0 ? static_cast<double>(st.kept) / st.candidates : 0.0;
  if (kept_fraction < options.min_kept_fraction)
    return {false, "not usable: only " + fmt(100 * kept_fraction, 0) + "% of the template lies within " +
                       fmt(options.correspondences.max_distance_end_mm) +
                       " mm of the scan (is this an upper-torso scan? are the landmarks right?)"};
  if (kept_mae_mm > options.max_surface_mae_mm)
    return {false, "not usable: mean template-to-scan distance " + fmt(kept_mae_mm, 2) + " mm exceeds " +
                       fmt(options.max_surface_mae_mm) + " mm"};
  return {true, "usable: " + fmt(100 * kept_fraction, 0) + "% of the template within " +
                    fmt(options.correspondences.max_distance_end_mm) + " mm of the scan, mean distance " +
                    fmt(kept_mae_mm, 2) + " mm"};
}

struct BodyAxes {
  Vec3 up, front;
};
std::optional<BodyAxes> fitted_body_axes(const model::RiggedModel& model, const Points& V, const Points& N,
                                         const model::PoseParams& params);

// Flags on the final surface V (detail included: what the user sees); the robust factor is the one
// the fit's last stage used, on the parametric model V_model.
std::vector<LandmarkCheck> check_landmarks(const model::RiggedModel& model, const Points& V, const Points& V_model,
                                           const model::PoseParams& params,
                                           const std::vector<LandmarkTarget>& landmarks, const FitOptions& options,
                                           const PlacedCheck& placed) {
  std::vector<LandmarkCheck> out;
  const std::vector<Vec3>& predicted = placed.predicted;
  const std::vector<double>& held_off = placed.held_off;
  for (const auto& t : landmarks) {
    LandmarkCheck c;
    c.name = t.name;
    c.distance_mm = (model_landmark_position(model, t.model_landmark, V, params) - t.position).norm();
    c.tolerance_mm = landmark_check_tolerance_mm(t.name, options.landmark_check_mm);
    const double fitted = (model_landmark_position(model, t.model_landmark, V_model, params) - t.position).norm();
    c.factor = options.refine.robust_landmarks ? robust_landmark_factor(fitted, c.tolerance_mm) : 1.0;
    if (out.size() < held_off.size()) c.factor *= held_off[out.size()];
    c.flagged = c.distance_mm > c.tolerance_mm;
    if (out.size() < predicted.size()) {
      c.predicted_distance_mm = (predicted[out.size()] - t.position).norm();
      c.predicted_tolerance_mm = placed_landmark_tolerance_mm(t.name, options.landmark_check_mm);
      c.flagged = c.flagged || c.predicted_distance_mm > c.predicted_tolerance_mm;
    }
    if (out.size() < placed.anatomy.size() && placed.anatomy[out.size()]) {
      const AnatomyCheck& a = *placed.anatomy[out.size()];
      c.anatomy_distance_mm = a.distance_mm;
      c.anatomy_tolerance_mm = a.tolerance_mm;
      c.anatomy = a.what;
      c.flagged = c.flagged || a.distance_mm > a.tolerance_mm;
    }
    if (out.size() < placed.flagged.size()) c.flagged = c.flagged || placed.flagged[out.size()];
    out.push_back(c);
  }
  return out;
}

// The search's choice into the summary: the one line, the report's details, a warning when a
// different orientation fits almost as well.
void summarize_orientation(const OrientationSearch& search, const FitOptions& options, FitSummary& summary) {
  OrientationSummary& o = summary.orientation;
  o.searched = true;
  o.chosen = search.hypotheses.empty() ? std::string("the shape's body frame") : search.hypotheses.front().name;
  o.runner_up = search.runner_up;
  o.margin = search.margin;
  o.confident = !(search.margin < options.orientation_min_margin);
  o.body_frame = search.body_frame;
  o.arm_abduction_deg[0] = search.arm_abduction_deg[0];
  o.arm_abduction_deg[1] = search.arm_abduction_deg[1];
  o.arm_pose = search.arm_pose;
  for (const auto& h : search.hypotheses) o.candidates.push_back({h.name, h.score, h.refined});
  const std::string margin =
      std::isfinite(search.margin) ? fmt(100 * search.margin, 0) + " % better than '" + search.runner_up + "'"
                                   : std::string("no other orientation fits");
  summary.initialization_detail = "landmark-free: body axes from the scan's shape, " +
                                  std::to_string(search.hypotheses.size()) + " orientations tried, kept '" +
                                  o.chosen + "' (" + margin + "); " + o.arm_pose + " (the scan is " +
                                  fmt(search.width_to_height, 2) + "x wider than high)";
  if (!o.confident)
    summary.warnings.push_back("the landmark-free orientation is uncertain: '" + o.chosen + "' fits only " +
                               fmt(100 * search.margin, 0) + " % better than '" + search.runner_up +
                               "'; check the landmarks and drawings, or give at least 3 landmarks");
}

bool is_given(const std::vector<LandmarkTarget>& given, const std::string& name) {
  return find_landmark(given, name) != nullptr;
}

// Targets for the nipples not in `given`: the breast's tip on the scan near each posed nipple.
std::vector<LandmarkTarget> breast_tip_targets(const model::RiggedModel& model, const Points& V,
                                               const model::PoseParams& params, const ScanTarget& scan,
                                               const std::vector<LandmarkTarget>& given) {
  std::vector<LandmarkTarget> out;
  const Points N = mesh::vertex_normals(V, model.rest.F);
  for (const char* name : {"nipple_R", "nipple_L"}) {
    const auto idx = model.landmark_index(name);
    if (!idx || is_given(given, name)) continue;
    const Vec3 nipple = model_landmark_position(model, *idx, V, params);
    if (const auto tip = breast_tip_on_scan(scan.mesh().V, V, N, nipple))
      out.push_back({name, *idx, *tip, landmark_weight(name)});
  }
  return out;
}

// The fitted body's axes: up along the sternum (xiphoid → notch), front the model's outward
// normals around both nipples (their lateral parts cancel), level. nullopt without those landmarks.
std::optional<BodyAxes> fitted_body_axes(const model::RiggedModel& model, const Points& V, const Points& N,
                                         const model::PoseParams& params) {
  Vec3 up = posed_vertical_axis(model, params);
  const auto notch = model.landmark_index("sternal_notch"), xiphoid = model.landmark_index("xiphoid");
  if (notch && xiphoid)
    up = (model_landmark_position(model, *notch, V, params) - model_landmark_position(model, *xiphoid, V, params))
             .normalized();
  Vec3 front = Vec3::Zero();
  for (const char* name : {"nipple_R", "nipple_L"}) {
    const auto idx = model.landmark_index(name);
    if (!idx) return std::nullopt;
    const Vec3 nipple = model_landmark_position(model, *idx, V, params);
    for (Index i = 0; i < V.rows(); ++i)
      if ((V.row(i).transpose() - nipple).norm() < 40.0) front += N.row(i).transpose();
  }
  front -= front.dot(up) * up;
  if (front.norm() <= 0) return std::nullopt;
  return BodyAxes{up, front.normalized()};
}

// The nipples held at the breast's tip, moved to the breast's apex on the scan (nipple_apex.h)
// around each fitted nipple of `V`, with the fitted sternum as the vertical; a nipple whose apex
// is not found keeps its target.
void hold_nipples_at_apex(const model::RiggedModel& model, const Points& V, const model::PoseParams& params,
                          const ScanTarget& scan, const std::vector<LandmarkTarget>& given,
                          std::vector<LandmarkTarget>& held) {
  const Points N = mesh::vertex_normals(V, model.rest.F);
  const auto axes = fitted_body_axes(model, V, N, params);
  if (!axes) return;
  for (const char* name : {"nipple_R", "nipple_L"}) {
    const auto idx = model.landmark_index(name);
    const auto at = std::find_if(held.begin(), held.end(), [&](const LandmarkTarget& t) { return t.name == name; });
    if (!idx || is_given(given, name) || at == held.end()) continue;
    const Vec3 nipple = model_landmark_position(model, *idx, V, params);
    if (const auto apex = nipple_apex_on_scan(scan.mesh().V, V, N, nipple, axes->up)) at->position = *apex;
  }
}

// Targets for the lowest breast points not in `held`: the fold found on the scan below each
// nipple held (given or the breast's tip), when the detector is sure.
std::vector<LandmarkTarget> breast_fold_targets(const model::RiggedModel& model, const Points& V,
                                                const model::PoseParams& params, const ScanTarget& scan,
                                                const std::vector<LandmarkTarget>& held) {
  std::vector<LandmarkTarget> out;
  const auto axes = fitted_body_axes(model, V, mesh::vertex_normals(V, model.rest.F), params);
  if (!axes) return out;
  for (const char* side : {"R", "L"}) {
    const std::string name = std::string("lowest_breast_") + side;
    const auto idx = model.landmark_index(name);
    const auto nipple = std::find_if(held.begin(), held.end(),
                                     [&](const LandmarkTarget& t) { return t.name == std::string("nipple_") + side; });
    if (!idx || nipple == held.end() || is_given(held, name)) continue;
    const Vec3 fitted = model_landmark_position(model, *idx, V, params);
    if (const auto fold = lowest_breast_on_scan(scan.mesh().V, nipple->position, fitted, axes->up, axes->front))
      out.push_back({name, *idx, *fold, landmark_weight(name)});
  }
  return out;
}

// The sternal notch when not given: where the manubrium meets the neck on the scan's midline.
std::vector<LandmarkTarget> jugular_notch_targets(const model::RiggedModel& model, const Points& V,
                                                  const model::PoseParams& params, const ScanTarget& scan,
                                                  const std::vector<LandmarkTarget>& given) {
  std::vector<LandmarkTarget> out;
  const auto idx = model.landmark_index("sternal_notch");
  if (!idx || is_given(given, "sternal_notch")) return out;
  const auto axes = fitted_body_axes(model, V, mesh::vertex_normals(V, model.rest.F), params);
  if (!axes) return out;
  const Vec3 fitted = model_landmark_position(model, *idx, V, params);
  if (const auto notch = jugular_notch_on_scan(scan.mesh().V, fitted, axes->up, axes->front))
    out.push_back({"sternal_notch", *idx, *notch, landmark_weight("sternal_notch")});
  return out;
}

// A landmark's position: its target in `held` when there is one, else the posed model's.
std::optional<Vec3> held_or_posed(const model::RiggedModel& model, const Points& V, const model::PoseParams& params,
                                  const std::vector<LandmarkTarget>& held, const std::string& name) {
  if (const LandmarkTarget* t = find_landmark(held, name)) return t->position;
  const auto idx = model.landmark_index(name);
  if (!idx) return std::nullopt;
  return model_landmark_position(model, *idx, V, params);
}

// The lowest breast points not given, placed again once the shape is fitted: by proportions of
// the held notch, the fitted xiphoid and the held nipples (breast_fold.h); each replaces the fold's
// target in `held` when found. With a subset of the landmarks given or none (`under_hanging_breasts`),
// where the breast hangs over the fold's height, at the bottom of its lower pole instead
// (hanging_breast_fold.h).
void place_folds_by_proportion(const model::RiggedModel& model, const Points& V, const model::PoseParams& params,
                               const ScanTarget& scan, const std::vector<LandmarkTarget>& given,
                               std::vector<LandmarkTarget>& held, bool under_hanging_breasts) {
  const auto notch = held_or_posed(model, V, params, held, "sternal_notch");
  const auto xiphoid = held_or_posed(model, V, params, held, "xiphoid");
  const auto right = held_or_posed(model, V, params, held, "nipple_R");
  const auto left = held_or_posed(model, V, params, held, "nipple_L");
  if (!notch || !xiphoid || !right || !left) return;
  for (const char side : {'R', 'L'}) {
    const std::string name = std::string("lowest_breast_") + side;
    const auto idx = model.landmark_index(name);
    const auto frame = sternum_frame(*notch, *xiphoid, *right, *left, side);
    if (!idx || !frame || is_given(given, name)) continue;
    const Vec3 fitted = model_landmark_position(model, *idx, V, params);
    const Vec3& tip = side == 'R' ? *right : *left;
    std::optional<Vec3> fold;
    const double height = -lowest_breast_drop_mm(*frame, -sternum_coordinates(*frame, tip).height);
    // Where the slice at that height meets a hanging breast's front: the bottom of its lower pole
    // (hanging_breast_fold.h); else, or when no fall is found below it, by proportions.
    if (under_hanging_breasts) fold = lowest_breast_if_hanging(scan.mesh().V, tip, fitted, *frame, height);
    if (!fold) fold = lowest_breast_by_proportion(scan.mesh().V, tip, fitted, *frame);
    if (!fold) continue;
    const LandmarkTarget target{name, *idx, *fold, landmark_weight(name)};
    const auto at = std::find_if(held.begin(), held.end(), [&](const LandmarkTarget& t) { return t.name == name; });
    if (at != held.end())
      *at = target;
    else
      held.push_back(target);
  }
}

// The notch and both nipples in `from` but no xiphoid held: the xiphoid held at the sternum's length
// those three predict, along the shaped model's sternum (sternum_length.h); the folds' and the
// shoulder's proportions are then taken from it. Appended to `held` when placed. `from` is the given
// landmarks when a subset is given, and `held` itself without landmarks (the jugular notch and the
// breasts' tips found on the scan).
void place_xiphoid_by_nipples(const model::RiggedModel& model, const Points& V, const model::PoseParams& params,
                              const std::vector<LandmarkTarget>& from, std::vector<LandmarkTarget>& held) {
  const auto idx = model.landmark_index("xiphoid");
  const LandmarkTarget* notch = find_landmark(from, "sternal_notch");
  const LandmarkTarget* right = find_landmark(from, "nipple_R");
  const LandmarkTarget* left = find_landmark(from, "nipple_L");
  if (!idx || !notch || !right || !left || is_given(held, "xiphoid")) return;
  const Vec3 fitted = model_landmark_position(model, *idx, V, params);
  if (const auto placed = xiphoid_by_nipples(notch->position, right->position, left->position, fitted))
    held.push_back({"xiphoid", *idx, *placed, landmark_weight("xiphoid")});
}

// The pectoral insertion of a hanging arm on the scan: at the anterior axillary fold
// (pectoral_insertion.h), moved along the arm to the sternum's proportion (shoulder_landmarks.h).
std::optional<Vec3> hanging_insertion(const model::RiggedModel& model, const Points& V, const model::PoseParams& params,
                                      const Points& S, const SternumFrame& frame, const Vec3& fitted,
                                      const Vec3& nipple, char side) {
  const auto arm = upper_arm_axis(model, V, params, std::string(1, side));
  if (!arm) return std::nullopt;
  const auto fold = pectoral_insertion_on_scan(S, fitted, *arm, frame.up, frame.front, nipple);
  if (!fold) return std::nullopt;
  if (const auto level = hanging_pectoral_insertion_on_scan(S, *fold, frame)) return level;
  return fold;
}

// Targets for the acromia, the mid-axillary points and the pectoral insertions not in `held`, in
// the sternum's frame of the held notch (the jugular notch on the scan) and the posed xiphoid:
// arms on boards (not found hanging by the orientation search's `arm_pose`, and reaching out
// sideways on the scan) the three by the sternum's proportions (shoulder_landmarks.h); arms
// hanging the pectoral insertion at the anterior axillary fold.
std::vector<LandmarkTarget> shoulder_targets(const model::RiggedModel& model, const Points& V,
                                             const model::PoseParams& params, const ScanTarget& scan,
                                             const std::vector<LandmarkTarget>& held, const std::string& arm_pose) {
  std::vector<LandmarkTarget> out;
  const auto notch = held_or_posed(model, V, params, held, "sternal_notch");
  const auto xiphoid = held_or_posed(model, V, params, held, "xiphoid");
  const auto right = held_or_posed(model, V, params, held, "nipple_R");
  const auto left = held_or_posed(model, V, params, held, "nipple_L");
  if (!notch || !xiphoid || !right || !left) return out;
  const Points& S = scan.mesh().V;
  for (const char side : {'R', 'L'}) {
    const auto frame = sternum_frame(*notch, *xiphoid, *right, *left, side);
    if (!frame) return out;
    const bool abducted = arm_pose.rfind("arms hanging", 0) != 0 && arms_abducted_on_scan(S, *frame);
    const bool hanging = !abducted && arm_pose.rfind("arms abducted", 0) != 0;
    if (!abducted && !hanging) continue;  // the search and the scan disagree
    for (const std::string kind : {"acromion_", "midaxillary_", "pectoral_insertion_"}) {
      const std::string name = kind + side;
      const auto idx = model.landmark_index(name);
      if (!idx || is_given(held, name) || (hanging && kind != "pectoral_insertion_")) continue;
      const Vec3 fitted = model_landmark_position(model, *idx, V, params);
      const auto found = hanging                 ? hanging_insertion(model, V, params, S, *frame, fitted,
                                                                     side == 'R' ? *right : *left, side)
                         : kind == "acromion_"    ? acromion_on_scan(S, fitted, *frame)
                         : kind == "midaxillary_" ? midaxillary_on_scan(S, fitted, *frame)
                                                  : abducted_pectoral_insertion_on_scan(S, *frame);
      if (found) out.push_back({name, *idx, *found, 1.0});
    }
  }
  return out;
}

// A fit stopped by the caller or by a numerical failure: no further stage or check runs on it.
bool cut_short(Termination t) { return t == Termination::Aborted || t == Termination::NumericalFailure; }

// The acromia, the mid-axillary points and the pectoral insertions (shoulder_targets).
bool is_shoulder_landmark(const std::string& name) {
  return name.rfind("acromion_", 0) == 0 || name.rfind("midaxillary_", 0) == 0 ||
         name.rfind("pectoral_insertion_", 0) == 0;
}

// The arm's landmarks with the arms hanging (the orientation search and the scan agree, as in
// shoulder_targets) and a subset of the landmarks given: the mid-axillary points not in `held` on
// the scan's chest wall in front of the fitted points (hanging_midaxillary.h), and the acromia not
// in `held` at the fitted points moved up and towards the midline (hanging_acromion.h).
std::vector<LandmarkTarget> hanging_arm_targets(const model::RiggedModel& model, const Points& V,
                                                const model::PoseParams& params, const ScanTarget& scan,
                                                const std::vector<LandmarkTarget>& held, const std::string& arm_pose) {
  std::vector<LandmarkTarget> out;
  const auto notch = held_or_posed(model, V, params, held, "sternal_notch");
  const auto xiphoid = held_or_posed(model, V, params, held, "xiphoid");
  const auto right = held_or_posed(model, V, params, held, "nipple_R");
  const auto left = held_or_posed(model, V, params, held, "nipple_L");
  if (!notch || !xiphoid || !right || !left || arm_pose.rfind("arms abducted", 0) == 0) return out;
  const Points& S = scan.mesh().V;
  for (const char side : {'R', 'L'}) {
    const auto frame = sternum_frame(*notch, *xiphoid, *right, *left, side);
    if (!frame || arms_abducted_on_scan(S, *frame)) return out;
    const std::string name = std::string("midaxillary_") + side;
    const auto idx = model.landmark_index(name);
    if (idx && !is_given(held, name))
      if (const auto found = hanging_midaxillary_on_scan(S, model_landmark_position(model, *idx, V, params), *frame))
        out.push_back({name, *idx, *found, 1.0});
    const std::string acromion = std::string("acromion_") + side;
    const auto a = model.landmark_index(acromion);
    if (a && !is_given(held, acromion))
      out.push_back({acromion, *a, hanging_acromion_target(model_landmark_position(model, *a, V, params), *frame), 1.0});
  }
  return out;
}

// With a subset of the landmarks given, the refine stage's iterations (both runs) times this.
constexpr int kSubsetRefineIterationFactor = 2;

// The weight of a mid-axillary target placed again on the refined model (landmark_weight: 0.1 for
// a given one, 1 for the shape stage's). Arms on boards the refined model's point stayed 5–6 mm
// from its target, most of it too high (the skin rises with the abducted arm); at 3 the fitted
// points come 1–2 mm nearer the truth (docs/REGISTRATION.md, Session 14).
constexpr double kReplacedMidaxillaryWeight = 3.0;

// With a subset of the landmarks given, the shoulder's targets placed again on the refined model V
// (shoulder_targets); `held` starts with the `given` landmarks, and a target not found again keeps
// its place. With the notch and the nipples given the shape stage's sternum is short (its xiphoid
// high): the supine pectoral insertions were held 10 mm too medial and the mid-axillary points
// 7 mm too high on the visible benchmark cases; on the refined model 7 and 5 mm (docs/REGISTRATION.md,
// Session 13). The lowest breast points keep the shape stage's (placed again they lost 2 mm).
std::vector<LandmarkTarget> shoulders_on_refined(const model::RiggedModel& model, const Points& V,
                                                 const model::PoseParams& params, const ScanTarget& scan,
                                                 size_t given, const std::vector<LandmarkTarget>& held,
                                                 const std::string& arm_pose) {
  std::vector<LandmarkTarget> out;
  for (size_t i = 0; i < held.size(); ++i)
    if (i < given || !is_shoulder_landmark(held[i].name)) out.push_back(held[i]);
  auto found = shoulder_targets(model, V, params, scan, out, arm_pose);
  for (auto& t : hanging_arm_targets(model, V, params, scan, out, arm_pose)) found.push_back(t);
  for (auto& t : found) {
    if (t.name.rfind("midaxillary_", 0) == 0) t.weight = kReplacedMidaxillaryWeight;
    out.push_back(t);
  }
  for (size_t i = given; i < held.size(); ++i)
    if (!is_given(out, held[i].name)) out.push_back(held[i]);
  return out;
}

std::string termination_message(const FitSummary& s) {
  const std::string stage = s.stages.empty() ? std::string("-") : s.stages.back().name;
  const int n = static_cast<int>(s.iterations.size());
  switch (s.termination) {
    case Termination::IterationCap:
      return "iteration cap: stage '" + stage + "' ran all its iterations (" + std::to_string(n) + " in all)";
    case Termination::Aborted: return "aborted by the caller after " + std::to_string(n) + " iterations";
    case Termination::NumericalFailure: return "numerical failure in stage '" + stage + "'";
    default:
      return std::string("converged (") + to_string(s.termination) + ") in stage '" + stage + "' after " +
             std::to_string(n) + " iterations";
  }
}

void finish_fit(const model::RiggedModel& model, ScanTarget& scan, Problem& problem, const model::PoseParams& params,
                const std::vector<LandmarkTarget>& landmarks, const FitOptions& options, const PlacedCheck& placed,
                FitResult& result, double checks_s);
void finish_surface(const model::RiggedModel& model, ScanTarget& scan, Problem& problem, const model::PoseParams& params,
                    const FitOptions& options, FitResult& result);
void finish_checks(const model::RiggedModel& model, const std::vector<LandmarkTarget>& landmarks,
                   const FitOptions& options, const PlacedCheck& placed, FitResult& result);

// Where the scan's anatomy and the other landmarks put each of the first `given` landmarks of
// `problem` (landmark_prediction.h), at the final correspondences (the anatomical targets held
// after them are not checked).
// With `steps`, also the parameters after each landmark's leave-one-out step.
std::vector<Vec3> predict_given(Problem& problem, const model::PoseParams& params, const FitOptions& options,
                                size_t given, std::vector<model::PoseParams>* steps = nullptr) {
  problem.evaluator().set_params(params);
  problem.update_correspondences(options.correspondences.max_distance_end_mm, 1, options.uses_reverse_term());
  problem.update_terms(options.refine.robust_landmarks);
  std::vector<Vec3> out = predict_left_out_landmarks(
      problem, params, active_parameters(problem.evaluator().layout(), options.refine, options.max_blendshapes), steps);
  out.resize(given);
  return out;
}

// The linear prediction of a landmark walked along the skin falls short (landmark_prediction.h):
// the landmarks it already moved most (at least half their tolerance; at most
// kRelinearizedLandmarks) are predicted again with re-linearised steps — those whose leave-one-out
// is sharp (relinearized_prediction_is_sharp: without a lowest breast point, a nipple or a
// mid-axillary point, the re-linearised model drifts as far as the landmark-free fit does).
constexpr int kRelinearizedLandmarks = 2;
constexpr int kRelinearizationSteps = 4;
// `linear_steps`: predict_given's parameters after each leave-one-out step (the walks' first step).
void relinearize_suspects(Problem& problem, const model::PoseParams& params, const FitOptions& options,
                          const std::vector<LandmarkTarget>& given, std::vector<Vec3>& predicted,
                          const std::vector<model::PoseParams>& linear_steps) {
  std::vector<std::pair<double, size_t>> suspects;
  for (size_t i = 0; i < given.size(); ++i) {
    const double ratio = (predicted[i] - given[i].position).norm() /
                         placed_landmark_tolerance_mm(given[i].name, options.landmark_check_mm);
    if (ratio >= 0.5 && relinearized_prediction_is_sharp(given[i].name)) suspects.emplace_back(-ratio, i);
  }
  std::sort(suspects.begin(), suspects.end());
  if (suspects.size() > kRelinearizedLandmarks) suspects.resize(kRelinearizedLandmarks);
  const auto active = active_parameters(problem.evaluator().layout(), options.refine, options.max_blendshapes);
  const Relinearization at_end{options.correspondences.max_distance_end_mm, options.uses_reverse_term(),
                               options.refine.robust_landmarks};
  for (const auto& [ratio, i] : suspects)
    predicted[i] = predict_left_out_relinearized(problem, params, active, i, kRelinearizationSteps, at_end,
                                                 i < linear_steps.size() ? &linear_steps[i] : nullptr);
}

// Each bilateral pair against its mirror image (bilateral_check.h), the check kept by the member
// it blames; the same asymmetry in `unblamed` for the member the pair's check leaves to the
// combined check only (bilateral_check.h unblamed_member: the other one of a pair within its
// tolerance; check_agreement, session 16). A pair beyond its tolerance blames by the members'
// predictions where they tell (bilateral_check.h blamed_by_prediction, session 18).
void check_pairs(const std::vector<LandmarkTarget>& given, const std::vector<Vec3>& predicted,
                 const FitOptions& options, std::vector<std::optional<AnatomyCheck>>& out,
                 std::vector<std::optional<AnatomyCheck>>& unblamed) {
  const auto index_of = [&](const std::string& name) {
    return static_cast<size_t>(
        std::find_if(given.begin(), given.end(), [&](const LandmarkTarget& t) { return t.name == name; }) -
        given.begin());
  };
  const auto ratio = [&](const std::string& name) {
    const size_t i = index_of(name);
    return i < predicted.size() ? (predicted[i] - given[i].position).norm() /
                                      placed_landmark_tolerance_mm(name, options.landmark_check_mm)
                                : 0.0;
  };
  for (BilateralCheck c : check_bilateral_pairs(given, options.landmark_check_mm)) {
    const bool both = blame_is_uncertain(c, ratio(c.right), ratio(c.left));
    c.blamed = blamed_by_prediction(c, ratio(c.right), ratio(c.left));
    const std::string& partner = c.blamed == c.right ? c.left : c.right;
    // A member's check against the mirror image of `of` (the other member).
    const auto mirror_of = [&](const std::string& of) {
      return AnatomyCheck{c.distance_mm, c.tolerance_mm,
                          "the mirror image of '" + of + "' across the other landmarks' midline, off " + c.axis +
                              (both ? "; one of the two is off, the proportions cannot tell which" : "")};
    };
    const size_t i = index_of(c.blamed);
    if (i < out.size() && !out[i]) out[i] = mirror_of(partner);
    if (const size_t j = both ? index_of(partner) : out.size(); j < out.size() && !out[j]) out[j] = mirror_of(c.blamed);
    const auto other = unblamed_member(c);
    if (const size_t j = other ? index_of(*other) : unblamed.size(); j < unblamed.size()) unblamed[j] = mirror_of(c.blamed);
  }
}

// The sternum's frame of one side ('R' or 'L') from the fitted notch, xiphoid and nipples
// (shoulder_landmarks.h sternum_frame); nullopt when the model lacks one of them or it is degenerate.
std::optional<SternumFrame> fitted_sternum_frame(const model::RiggedModel& model, const Points& V,
                                                 const model::PoseParams& params, char side) {
  Vec3 p[4];
  const char* names[4] = {"sternal_notch", "xiphoid", "nipple_R", "nipple_L"};
  for (int k = 0; k < 4; ++k) {
    const auto idx = model.landmark_index(names[k]);
    if (!idx) return std::nullopt;
    p[k] = model_landmark_position(model, *idx, V, params);
  }
  return sternum_frame(p[0], p[1], p[2], p[3], side);
}

// Each given pectoral insertion's upper arm axis (pectoral_insertion.h upper_arm_axis) at the
// insertion's own leave-one-out step (predict_given's `steps`): the arm where the scan and the
// other landmarks put it. The fitted arm follows a misplaced insertion — where the scan ends the arm
// is weakly held, and the fit turns it towards the click (a validation case's insertion walked
// 40 mm: the upper arm turned by 24°), so the insertion's check read the click's own arm
// (docs/REGISTRATION.md, session 22). nullopt for a side without a given insertion or a step.
using InsertionArms = std::array<std::optional<Vec3>, 2>;  // right, left
// Only the vertices the axis reads are posed (upper_arm_axis_rows: the same bits as posing the whole
// mesh); the evaluator stays where it is.
InsertionArms left_out_insertion_arms(const model::RiggedModel& model, const model::PoseEvaluator& evaluator,
                                      const std::vector<LandmarkTarget>& given,
                                      const std::vector<model::PoseParams>& steps) {
  InsertionArms arms;
  Points V;
  for (size_t i = 0; i < given.size() && i < steps.size(); ++i)
    for (int side = 0; side < 2; ++side) {
      const std::string s = side == 0 ? "R" : "L";
      if (given[i].name != "pectoral_insertion_" + s) continue;
      if (V.rows() == 0) V = Points::Zero(evaluator.vertices().rows(), 3);
      evaluator.pose_rows(steps[i], upper_arm_axis_rows(model, s), V);
      arms[static_cast<size_t>(side)] = upper_arm_axis(model, V, steps[i], s);
    }
  return arms;
}

// Each given pectoral insertion against the same side's acromion and the arm (pectoral_check.h) —
// the arm at the insertion's leave-one-out step where there is one (`arms`), else the fitted arm —
// in the fitted sternum's frame; skipped when that acromion is suspect itself (beyond its
// prediction's or its pair's tolerance: the reference would be wrong).
void check_insertions(const model::RiggedModel& model, const Points& V, const model::PoseParams& params,
                      const std::vector<LandmarkTarget>& given, const std::vector<Vec3>& predicted,
                      const InsertionArms& arms, const FitOptions& options,
                      std::vector<std::optional<AnatomyCheck>>& out) {
  const auto index_of = [&](const std::string& name) {
    return static_cast<size_t>(
        std::find_if(given.begin(), given.end(), [&](const LandmarkTarget& t) { return t.name == name; }) -
        given.begin());
  };
  for (const char side : {'R', 'L'}) {
    const std::string s(1, side);
    const size_t i = index_of("pectoral_insertion_" + s), a = index_of("acromion_" + s);
    if (i >= given.size() || a >= given.size() || out[i]) continue;
    const bool acromion_suspect =
        (out[a] && out[a]->distance_mm > out[a]->tolerance_mm) ||
        (a < predicted.size() && (predicted[a] - given[a].position).norm() >
                                     placed_landmark_tolerance_mm(given[a].name, options.landmark_check_mm));
    const auto frame = fitted_sternum_frame(model, V, params, side);
    const auto& left_out = arms[side == 'R' ? 0 : 1];
    const auto arm = left_out ? left_out : upper_arm_axis(model, V, params, s);
    if (acromion_suspect || !frame || !arm) continue;
    const PectoralCheck c =
        check_pectoral_insertion(*frame, *arm, given[i].position, given[a].position, options.landmark_check_mm);
    out[i] = AnatomyCheck{c.distance_mm, c.tolerance_mm,
                          "where 'acromion_" + s + (left_out ? "' and the arm fitted without it" : "' and the fitted arm") +
                              " put it"};
  }
}

// `c` into `slot` when it is flagged and farther beyond its tolerance than the check already there.
void keep_if_worse(std::optional<AnatomyCheck>& slot, AnatomyCheck c) {
  const auto beyond = [](const AnatomyCheck& a) { return a.distance_mm / a.tolerance_mm; };
  if (!(c.distance_mm > c.tolerance_mm)) return;
  if (!slot || !(slot->distance_mm > slot->tolerance_mm) || beyond(c) > beyond(*slot)) slot = std::move(c);
}

// The scan's outward vertex normals for the anatomy checks, as `const Points&` where a check takes
// them: the index's own (ScanTarget::vertex_normals) when the normal sign is +1 — the same bits as
// the product with the sign, without a copy of #V × 3 doubles per fit — else their negation,
// computed once on first use.
class OutwardScanNormals {
 public:
  explicit OutwardScanNormals(const ScanTarget& scan) : scan_(scan) {}
  operator const Points&() {  // NOLINT(google-explicit-constructor): passed where Points are
    if (scan_.normal_sign() == 1.0) return scan_.vertex_normals();
    if (flipped_.rows() == 0) flipped_ = scan_.normal_sign() * scan_.vertex_normals();
    return flipped_;
  }

 private:
  const ScanTarget& scan_;
  Points flipped_;
};

// The scan searches of the anatomy checks around one given nipple: the breast's tip and the
// nipple's bump around where the other landmarks put it (the fitted one without predictions), the
// breast's apex around it (the given one without predictions; searched only with the fitted body's
// axes and sternum frame). nullopt where not found.
struct NippleSearch {
  std::optional<Vec3> tip, apex;
  std::optional<NippleBump> bump;
};

// The scan around a nipple its tip and apex are searched on: their axis' radius (40 mm).
constexpr double kNippleSkinRadiusMm = 40.0;

// The searches of every given nipple (empty slots for the other landmarks). They read only the
// scan and the fitted model, and each writes its own slot: with options.threads >= 2 they run side
// by side, the same bits as one after the other. The skin's labels (ScanTarget::skin: a pass over
// every scan triangle, serial, on the target's first fit only) are needed by the tips and apexes
// only: they are computed beside the bumps, then the tips and apexes of the nipples side by side,
// each on the skin around it through the scan's index.
std::vector<NippleSearch> search_nipples(const model::RiggedModel& model, const Points& V,
                                         const model::PoseParams& params, const ScanTarget& scan,
                                         const std::optional<BodyAxes>& axes, const std::vector<LandmarkTarget>& given,
                                         const std::vector<Vec3>& predicted, const FitOptions& options,
                                         OutwardScanNormals& scan_N) {
  std::vector<NippleSearch> out(given.size());
  std::vector<size_t> nipples;
  for (size_t i = 0; i < given.size(); ++i)
    if (given[i].name == "nipple_R" || given[i].name == "nipple_L") nipples.push_back(i);
  if (nipples.empty()) return out;
  const Points& N = scan_N;  // computed here once, read by both nipples
  const auto near_of = [&](size_t i) {
    return i < predicted.size() ? predicted[i] : model_landmark_position(model, given[i].model_landmark, V, params);
  };
  for_each_chunk(static_cast<Index>(nipples.size()) + 1, 1, options.threads, [&](Index chunk, Index, Index) {
    if (chunk == 0) {
      scan.skin();  // labelled here the target's first time (chunk 0; the bumps chunks 1, 2)
      return;
    }
    const size_t i = nipples[static_cast<size_t>(chunk - 1)];
    out[i].bump = nipple_bump_on_scan(scan.index(), N, near_of(i));
  });
  for_each_chunk(static_cast<Index>(nipples.size()), 1, options.threads, [&](Index chunk, Index, Index) {
    const size_t i = nipples[static_cast<size_t>(chunk)];
    const LandmarkTarget& t = given[i];
    const Vec3 near = near_of(i);
    NippleSearch& found = out[i];
    // On the skin only: a floating fragment in front of the breast is not its tip (session 20).
    const SkinPatch around = skin_around(scan.index(), N, scan.skin(), near, kNippleSkinRadiusMm);
    found.tip = breast_tip_on_scan(around.V, around.V, around.N, near);
    const Vec3 apex_centre = i < predicted.size() ? predicted[i] : t.position;
    if (axes && fitted_sternum_frame(model, V, params, t.name.back())) {
      const SkinPatch apex_skin =
          apex_centre == near ? SkinPatch{} : skin_around(scan.index(), N, scan.skin(), apex_centre, kNippleSkinRadiusMm);
      const SkinPatch& a = apex_centre == near ? around : apex_skin;
      found.apex = nipple_apex_on_scan(a.V, a.V, a.N, apex_centre, axes->up);
    }
  });
  return out;
}

// Session 13 (docs/REGISTRATION.md): the prediction and the anatomical check agreeing
// (combined_check.h), the nipples against the breast's apex (nipple_apex_check.h), the xiphoid
// against the lowest breast points' height (xiphoid_check.h). Each takes a landmark's anatomical
// check when it flags it and is farther beyond than the one there; `out` holds the earlier checks,
// `nipples` the apexes found (search_nipples).
// A pair's member not blamed by its check (`unblamed`, check_pairs) enters the combined check with
// the pair's asymmetry when it has no check of its own (session 16).
void check_agreement(const model::RiggedModel& model, const Points& V, const model::PoseParams& params,
                     const std::optional<BodyAxes>& axes,
                     const std::vector<LandmarkTarget>& given, const std::vector<Vec3>& predicted,
                     const FitOptions& options, const std::vector<NippleSearch>& nipples,
                     std::vector<std::optional<AnatomyCheck>>& out,
                     const std::vector<std::optional<AnatomyCheck>>& unblamed) {
  std::vector<std::optional<AnatomyCheck>> before = out;
  for (size_t i = 0; i < before.size() && i < unblamed.size(); ++i)
    if (!before[i]) before[i] = unblamed[i];
  for (size_t i = 0; i < given.size() && i < predicted.size(); ++i) {
    if (!before[i]) continue;
    const double ratio = (predicted[i] - given[i].position).norm() /
                         placed_landmark_tolerance_mm(given[i].name, options.landmark_check_mm);
    const auto tolerance = combined_anatomy_tolerance_mm(given[i].name, ratio, before[i]->tolerance_mm);
    if (tolerance)
      keep_if_worse(out[i], AnatomyCheck{before[i]->distance_mm, std::max(*tolerance, 0.25 * before[i]->tolerance_mm),
                                         before[i]->what + ", with where the other landmarks put it " +
                                             fmt(100 * ratio, 0) + " % of its tolerance off too"});
  }
  if (!axes) return;
  // Each given nipple's height above its apex, for its partner's rule (nipple_apex_check.h).
  std::vector<std::optional<double>> height(given.size());
  std::vector<std::optional<SternumFrame>> frames(given.size());
  for (size_t i = 0; i < given.size(); ++i) {
    const std::string& name = given[i].name;
    if (name != "nipple_R" && name != "nipple_L") continue;
    frames[i] = fitted_sternum_frame(model, V, params, name.back());
    if (frames[i] && nipples[i].apex) height[i] = height_above_apex_mm(*frames[i], given[i].position, *nipples[i].apex);
  }
  for (size_t i = 0; i < given.size(); ++i) {
    if (!height[i]) continue;
    const LandmarkTarget* partner = find_landmark(given, given[i].name == "nipple_R" ? "nipple_L" : "nipple_R");
    const std::optional<double> partner_up = partner && options.nipple_below_apex_check
                                                 ? height[static_cast<size_t>(partner - given.data())]
                                                 : std::nullopt;
    const double tip_ratio = before[i] ? before[i]->distance_mm / before[i]->tolerance_mm : 0.0;
    const NippleApexCheck c = check_nipple_apex(*frames[i], given[i].position, *nipples[i].apex, tip_ratio, partner_up);
    keep_if_worse(out[i], AnatomyCheck{c.distance_mm, c.tolerance_mm,
                                       "the breast's apex on the scan" + (c.flagged() ? " (" + c.rule + ")" : "")});
  }
  const LandmarkTarget *n = find_landmark(given, "sternal_notch"), *x = find_landmark(given, "xiphoid"),
                       *r = find_landmark(given, "lowest_breast_R"), *l = find_landmark(given, "lowest_breast_L");
  if (n && x && r && l) {
    const size_t i = static_cast<size_t>(x - given.data());
    const double residual = xiphoid_residual_mm(n->position, x->position, r->position, l->position, axes->up);
    if (residual > 0)
      keep_if_worse(out[i], AnatomyCheck{residual, kXiphoidTooLowMm * options.landmark_check_mm / 15.0,
                                         "the sternum's length the lowest breast points give (too low by that)"});
  }
}

// Session 15 (docs/REGISTRATION.md): each given nipple against the nipple's own bump on the scan
// (nipple_bump_check.h), searched around its prediction (the fitted one without predictions;
// search_nipples).
void check_nipple_bumps(const std::vector<LandmarkTarget>& given, const FitOptions& options,
                        const std::vector<NippleSearch>& nipples, std::vector<std::optional<AnatomyCheck>>& out) {
  for (size_t i = 0; i < given.size(); ++i) {
    const LandmarkTarget& t = given[i];
    const auto& bump = nipples[i].bump;
    if ((t.name != "nipple_R" && t.name != "nipple_L") || !bump) continue;
    const NippleBumpCheck c = check_nipple_bump(t.position, *bump, options.landmark_check_mm);
    keep_if_worse(out[i], AnatomyCheck{c.distance_mm, c.tolerance_mm, "the nipple's bump on the scan"});
  }
}

// Each given nipple and sternal notch against its own definition on the scan, searched around
// where the other landmarks put it (`predicted`; the fitted one without predictions, since the
// fit follows a wrong click): the nipples at the breast's tip (landmark_check.h; along the scan's
// own normals: the fitted model's turn with a wrongly placed nipple), the notch at the jugular
// notch on the other landmarks' midline (midline_notch_check.h); the acromia, mid-axillary and
// lowest breast points against their partner's mirror image (check_pairs); the pectoral insertions
// against their acromion and the fitted arm (check_insertions).
std::vector<std::optional<AnatomyCheck>> check_anatomy(const model::RiggedModel& model, Problem& problem,
                                                       const model::PoseParams& params, const ScanTarget& scan,
                                                       const std::vector<LandmarkTarget>& given,
                                                       const std::vector<Vec3>& predicted, const InsertionArms& arms,
                                                       const FitOptions& options) {
  std::vector<std::optional<AnatomyCheck>> out(given.size());
  auto& ev = problem.evaluator();
  ev.set_params(params);
  const Points& V = ev.vertices();
  const auto axes = fitted_body_axes(model, V, mesh::vertex_normals(V, model.rest.F), params);
  OutwardScanNormals scan_N(scan);  // the index's own normals (negated once, if need be)
  const std::vector<NippleSearch> nipples =
      search_nipples(model, V, params, scan, axes, given, predicted, options, scan_N);
  for (size_t i = 0; i < given.size(); ++i) {
    const LandmarkTarget& t = given[i];
    if (t.name == "nipple_R" || t.name == "nipple_L") {
      if (const auto& tip = nipples[i].tip)
        out[i] = AnatomyCheck{(*tip - t.position).norm(), options.nipple_tip_check_mm, "the breast's tip on the scan"};
    } else if (t.name == "sternal_notch" && axes) {
      const Vec3 near =
          i < predicted.size() ? predicted[i] : model_landmark_position(model, t.model_landmark, V, params);
      if (const auto notch = check_notch_on_midline(scan.mesh().V, given, near, axes->up, axes->front, t.position,
                                                    options.notch_check_mm))
        out[i] = AnatomyCheck{notch->distance_mm, notch->tolerance_mm, "the jugular notch on the scan's midline"};
    }
  }
  std::vector<std::optional<AnatomyCheck>> unblamed(given.size());
  check_pairs(given, predicted, options, out, unblamed);
  check_insertions(model, V, params, given, predicted, arms, options, out);
  check_agreement(model, V, params, axes, given, predicted, options, nipples, out, unblamed);
  check_nipple_bumps(given, options, nipples, out);
  return out;
}

// Checks the given landmarks against their predictions; those beyond their tolerance get their
// weight multiplied by (tolerance / distance)² and, with `refit`, the model is stepped to where the
// others put it (leave_out_landmarks) and the refine stage is run again: one bad click cannot drag
// the fit. (The workstation's warm re-fit only reports: the user is placing the landmarks.)
PlacedCheck hold_off_misplaced(const model::RiggedModel& model, ScanTarget& scan, std::unique_ptr<Problem>& problem,
                               model::PoseParams& params, const std::vector<LandmarkTarget>& given,
                               const FitOptions& options, FitSummary& summary, const IterationCallback& on_iteration,
                               bool refit = true) {
  PlacedCheck out;
  out.held_off.assign(given.size(), 1.0);
  out.flagged.assign(given.size(), false);
  if (cut_short(summary.termination)) return out;
  InsertionArms arms;
  if (given.size() >= kMinLandmarksToPredict) {
    std::vector<model::PoseParams> linear_steps;
    out.predicted = predict_given(*problem, params, options, given.size(), &linear_steps);
    relinearize_suspects(*problem, params, options, given, out.predicted, linear_steps);
    arms = left_out_insertion_arms(model, problem->evaluator(), given, linear_steps);
  }
  out.anatomy = check_anatomy(model, *problem, params, scan, given, out.predicted, arms, options);
  std::vector<size_t> off;
  for (size_t i = 0; i < given.size(); ++i) {
    double factor = 1.0;
    if (i < out.predicted.size())
      factor = robust_landmark_factor((out.predicted[i] - given[i].position).norm(),
                                      placed_landmark_tolerance_mm(given[i].name, options.landmark_check_mm));
    if (out.anatomy[i]) factor = std::min(factor, robust_landmark_factor(out.anatomy[i]->distance_mm,
                                                                         out.anatomy[i]->tolerance_mm));
    if (factor >= 1.0) continue;
    off.push_back(i);
    out.flagged[i] = true;
    out.held_off[i] = factor;
  }
  if (!refit) out.held_off.assign(given.size(), 1.0);
  if (off.empty() || !refit || out.predicted.empty()) return out;
  params = leave_out_landmarks(*problem, params,
                               active_parameters(problem->evaluator().layout(), options.refine, options.max_blendshapes),
                               off);
  std::vector<LandmarkTarget> held = problem->landmarks();
  for (size_t i : off) held[i].weight *= out.held_off[i];
  problem = std::make_unique<Problem>(model, scan, options, held);
  summary.termination = minimize_stages(*problem, {options.refine}, params, summary, on_iteration);
  if (!cut_short(summary.termination)) {
    // The landmarks held off keep the prediction that flagged them (the refit no longer follows them).
    std::vector<Vec3> after = predict_given(*problem, params, options, given.size());
    for (size_t i : off) after[i] = out.predicted[i];
    out.predicted = std::move(after);
  }
  return out;
}

}  // namespace

std::vector<LandmarkTarget> select_landmarks(std::vector<LandmarkTarget> targets, const FitOptions& options) {
  if (!options.use_landmarks) return {};
  if (options.max_landmarks >= 0 && static_cast<int>(targets.size()) > options.max_landmarks)
    targets.resize(static_cast<size_t>(options.max_landmarks));
  return targets;
}

FitResult register_template(const model::RiggedModel& model, ScanTarget& scan, std::vector<LandmarkTarget> landmarks,
                            const FitOptions& options, const IterationCallback& on_iteration) {
  options.validate();
  Timer timer, phase;
  FitResult result;
  FitSummary& summary = result.summary;

  landmarks = select_landmarks(std::move(landmarks), options);

  model::PoseParams params = model::PoseParams::identity(model);
  if (landmarks.size() >= 3) {
    const LandmarkInitialization init = initialize_from_landmarks(model, landmarks);
    params.global = init.similarity;
    summary.initialization = "landmarks";
    summary.initialization_detail = "from " + std::to_string(landmarks.size()) + " landmarks (RMS " +
                                    fmt(init.rms_mm) + " mm after the similarity)";
    if (init.swapped)
      summary.warnings.push_back("the landmarks' _R/_L labels look swapped (RMS " + fmt(init.swapped_rms_mm) +
                                 " mm as given, " + fmt(init.rms_mm) + " mm with R and L exchanged): corrected");
  } else {
    if (!landmarks.empty())
      summary.warnings.push_back("fewer than 3 landmarks: initialised without landmarks; the " +
                                 std::to_string(landmarks.size()) + " given are used in the fit");
    const OrientationSearch search = search_orientation(model, scan, options);
    params = search.params;
    summary.initialization = "landmark-free";
    summarize_orientation(search, options, summary);
  }
  summary.landmarks_used = static_cast<int>(landmarks.size());

  auto problem_ptr = std::make_unique<Problem>(model, scan, options, landmarks);
  problem_ptr->evaluator().set_params(params);
  problem_ptr->orient_scan_normals(options.correspondences.max_distance_start_mm);
  if (landmarks.size() >= 3) initialize_arms(model, scan, params, false, options.threads);  // landmark-free: done by the search
  summary.timings.push_back({"initialization", phase.seconds()});

  std::vector<StageOptions> stages;
  if (landmarks.size() >= 3) stages.push_back(options.landmark_pose);
  for (const auto& s : {options.rigid, options.pose, options.shape, options.refine}) stages.push_back(s);
  // Automatic correspondence intervals: every 2nd iteration when all the landmarks hold the model
  // (measured: with 3 landmarks or none, every iteration is needed).
  const bool all_landmarks = landmarks.size() >= 3 && landmarks.size() >= model.landmarks.size();
  for (auto& s : stages)
    if (s.correspondence_interval == 0) s.correspondence_interval = all_landmarks ? 2 : 1;
  // Anatomy held where no landmark was given: without landmarks the breasts can slide over the
  // scan (the surface barely changes, the nipples move) and the lower pole stays too high; once
  // posed, the breast tips, the folds and the jugular notch found on the scan hold the nipples, the
  // lowest breast points and the notch for the shape and refine stages.
  const bool hold_nipples = landmarks.size() < 3 && options.anatomical_nipples;
  // Also with a subset such as the notch and the nipples (the fold is refused far below the fitted
  // lower pole: docs/REGISTRATION.md).
  const bool hold_folds = options.anatomical_lowest_breast &&
                          !(is_given(landmarks, "lowest_breast_R") && is_given(landmarks, "lowest_breast_L"));
  const bool hold_notch = options.anatomical_notch && !is_given(landmarks, "sternal_notch");
  const bool hold_shoulders = options.anatomical_shoulders && landmarks.size() < model.landmarks.size();
  // A subset of the landmarks given (3 or more, not all): the xiphoid placed by the nipples, the
  // folds by proportion with it, and the refine stage run longer with the shoulders placed twice.
  const bool subset = landmarks.size() >= 3 && hold_shoulders;
  if (hold_nipples || hold_folds || hold_notch || hold_shoulders) {
    const auto coarse_end = stages.end() - 2;  // shape and refine follow
    const std::vector<StageOptions> coarse(stages.begin(), coarse_end);
    summary.termination = minimize_stages(*problem_ptr, coarse, params, summary, on_iteration);
    if (!cut_short(summary.termination)) {
      problem_ptr->evaluator().set_params(params);
      const Points& V = problem_ptr->evaluator().vertices();
      std::vector<LandmarkTarget> held = landmarks;
      if (hold_nipples)
        for (auto& t : breast_tip_targets(model, V, params, scan, landmarks)) held.push_back(t);
      if (hold_folds)
        for (auto& t : breast_fold_targets(model, V, params, scan, held)) held.push_back(t);
      if (hold_notch)
        for (auto& t : jugular_notch_targets(model, V, params, scan, landmarks)) held.push_back(t);
      summary.anatomical_landmarks = static_cast<int>(held.size() - landmarks.size());
      for (size_t i = landmarks.size(); i < held.size(); ++i) summary.anatomical_landmark_names.push_back(held[i].name);
      problem_ptr = std::make_unique<Problem>(model, scan, options, held);
      if (hold_shoulders || hold_folds) {
        // The shoulder's landmarks once the shape is fitted (from the posed model the sternum is
        // too short and the mid-axillary points came out higher), held for the refine stage; the
        // folds placed again there by proportions.
        summary.termination = minimize_stages(*problem_ptr, {coarse_end, coarse_end + 1}, params, summary, on_iteration);
        if (!cut_short(summary.termination)) {
          problem_ptr->evaluator().set_params(params);
          const Points& shaped = problem_ptr->evaluator().vertices();
          const size_t before = held.size();
          // A subset given or none: the xiphoid by the sternum's length (from the given notch and
          // nipples, or the ones held on the scan), and the folds under hanging breasts.
          const bool by_proportions = subset || landmarks.empty();
          if (by_proportions) place_xiphoid_by_nipples(model, shaped, params, subset ? landmarks : held, held);
          if (hold_folds) place_folds_by_proportion(model, shaped, params, scan, landmarks, held, by_proportions);
          if (hold_shoulders)
            for (auto& t : shoulder_targets(model, shaped, params, scan, held, summary.orientation.arm_pose))
              held.push_back(t);
          // The nipples moved from the breast's tip to its apex once the folds and the shoulders are
          // placed (they keep the tip: placed from the apex, the contours came out worse).
          if (hold_nipples && options.anatomical_nipple_apex)
            hold_nipples_at_apex(model, shaped, params, scan, landmarks, held);
          for (size_t i = before; i < held.size(); ++i) summary.anatomical_landmark_names.push_back(held[i].name);
          summary.anatomical_landmarks = static_cast<int>(held.size() - landmarks.size());
          problem_ptr = std::make_unique<Problem>(model, scan, options, held);
          // A subset given: the refine stage with twice its iterations, here and once more below (in its
          // 3 iterations the model stayed 2–5 mm short of the targets; docs/REGISTRATION.md, Session 14).
          std::vector<StageOptions> refine(coarse_end + 1, stages.end());
          if (subset)
            for (auto& s : refine) s.max_iterations *= kSubsetRefineIterationFactor;
          summary.termination = minimize_stages(*problem_ptr, refine, params, summary, on_iteration);
          if (subset && !cut_short(summary.termination)) {
            // A subset given: the shoulder's landmarks placed again on the refined model, refined once more.
            problem_ptr->evaluator().set_params(params);
            held = shoulders_on_refined(model, problem_ptr->evaluator().vertices(), params, scan, landmarks.size(), held,
                                        summary.orientation.arm_pose);
            for (size_t i = landmarks.size(); i < held.size(); ++i)
              if (std::find(summary.anatomical_landmark_names.begin(), summary.anatomical_landmark_names.end(),
                            held[i].name) == summary.anatomical_landmark_names.end())
                summary.anatomical_landmark_names.push_back(held[i].name);
            summary.anatomical_landmarks = static_cast<int>(held.size() - landmarks.size());
            problem_ptr = std::make_unique<Problem>(model, scan, options, held);
            summary.termination = minimize_stages(*problem_ptr, refine, params, summary, on_iteration);
          }
        }
      } else {
        summary.termination = minimize_stages(*problem_ptr, {coarse_end, stages.end()}, params, summary, on_iteration);
      }
    }
  } else {
    summary.termination = minimize_stages(*problem_ptr, stages, params, summary, on_iteration);
  }
  // The placed landmarks' checks are the phase "landmark_checks": hold_off_misplaced without the
  // refine stage it may run again (timed as its own "stage:refine"), and finish_checks.
  Timer checks;
  const size_t phases_before = summary.timings.size();
  const PlacedCheck placed =
      hold_off_misplaced(model, scan, problem_ptr, params, landmarks, options, summary, on_iteration);
  double checks_s = checks.seconds();
  for (size_t k = phases_before; k < summary.timings.size(); ++k) checks_s -= summary.timings[k].seconds;
  finish_fit(model, scan, *problem_ptr, params, landmarks, options, placed, result, checks_s);
  summary.seconds = timer.seconds();
  return result;
}

namespace {

// The re-fit's own schedule (RefitOptions) on top of `options`.
FitOptions refit_options(const FitOptions& options) {
  FitOptions warm = options;
  if (options.refit.final_threshold) warm.correspondences.max_distance_start_mm = options.correspondences.max_distance_end_mm;
  warm.refine.max_iterations = options.refit.max_iterations;
  warm.solver.vertex_tolerance_mm = std::max(options.solver.vertex_tolerance_mm, options.refit.vertex_tolerance_mm);
  return warm;
}

}  // namespace

FitResult refit_surface(const model::RiggedModel& model, ScanTarget& scan, std::vector<LandmarkTarget> landmarks,
                        const FitOptions& options, const model::PoseParams& start,
                        const IterationCallback& on_iteration, const Problem::CorrespondenceState* start_correspondences) {
  options.validate();
  if (start.bones.size() != model.bones.size() || start.alpha.size() != static_cast<Eigen::Index>(model.blendshapes.size()))
    throw InvalidInput("warm start: the parameters are not those of template '" + model.name + "'");
  if (!options.use_landmarks) landmarks.clear();
  Timer timer, phase;
  FitResult result;
  FitSummary& summary = result.summary;
  summary.initialization = "warm start";
  summary.landmarks_used = static_cast<int>(landmarks.size());
  model::PoseParams params = start;
  const FitOptions warm = refit_options(options);  // outlives the problem, which keeps a reference
  Problem problem(model, scan, warm, landmarks);
  problem.evaluator().set_params(params);
  if (start_correspondences) problem.restore_correspondences(*start_correspondences);
  summary.timings.push_back({"initialization", phase.seconds()});
  summary.termination = minimize_stages(problem, {warm.refine}, params, summary, on_iteration);
  finish_surface(model, scan, problem, params, warm, result);
  result.landmarks = landmarks;
  summary.seconds = timer.seconds();
  return result;
}

void check_refit(const model::RiggedModel& model, ScanTarget& scan, const FitOptions& options, FitResult& result) {
  Timer phase;
  const FitOptions warm = refit_options(options);
  const std::vector<LandmarkTarget> landmarks = result.landmarks;
  // A re-fit's landmark check only reports (hold_off_misplaced without its refit): its predictions
  // need the fitted parameters alone, on a problem of their own (the same terms at the same
  // parameters as the re-fit's), from the final state's pairs (the same, not searched again).
  auto own = std::make_unique<Problem>(model, scan, warm, landmarks);
  if (result.final_correspondences) own->restore_correspondences(*result.final_correspondences);
  model::PoseParams at = result.params;
  FitSummary read_only = result.summary;
  const PlacedCheck placed = hold_off_misplaced(model, scan, own, at, landmarks, warm, read_only, {}, false);
  finish_checks(model, landmarks, warm, placed, result);
  result.summary.timings.push_back({"landmark_checks", phase.seconds()});
  result.summary.seconds += phase.seconds();
}

FitResult refit_template(const model::RiggedModel& model, ScanTarget& scan, std::vector<LandmarkTarget> landmarks,
                         const FitOptions& options, const model::PoseParams& start,
                         const IterationCallback& on_iteration) {
  FitResult result = refit_surface(model, scan, std::move(landmarks), options, start, on_iteration);
  check_refit(model, scan, options, result);
  return result;
}

namespace {

// The end of every fit: the final state at the final threshold, the verdict, the surface detail
// and the landmark checks; the phase "landmark_checks" last, `checks_s` (the checks' time before)
// with finish_checks' own.
void finish_fit(const model::RiggedModel& model, ScanTarget& scan, Problem& problem, const model::PoseParams& params,
                const std::vector<LandmarkTarget>& landmarks, const FitOptions& options, const PlacedCheck& placed,
                FitResult& result, double checks_s) {
  finish_surface(model, scan, problem, params, options, result);
  Timer phase;
  finish_checks(model, landmarks, options, placed, result);
  result.summary.timings.push_back({"landmark_checks", checks_s + phase.seconds()});
}

// finish_fit's first part: the final state at the final threshold, the verdict, the surface detail.
void finish_surface(const model::RiggedModel& model, ScanTarget& scan, Problem& problem, const model::PoseParams& params,
                    const FitOptions& options, FitResult& result) {
  FitSummary& summary = result.summary;
  Timer phase;
  problem.evaluator().set_params(params);
  problem.update_correspondences(options.correspondences.max_distance_end_mm, 1, options.uses_reverse_term());
  problem.update_terms(options.refine.robust_landmarks);
  summary.final_energy = problem.evaluate(nullptr);
  summary.final_correspondences = problem.stats();
  summary.final_reverse_correspondences = problem.reverse_stats();
  summary.kept_mae_mm = problem.kept_mae_mm();
  if (summary.termination != Termination::Aborted && !std::isfinite(summary.final_energy.total()))
    summary.termination = Termination::NumericalFailure;
  summary.termination_message = termination_message(summary);
  summary.verdict = judge(options, problem, summary.termination, summary.kept_mae_mm);
  summary.message = summary.usable() ? summary.termination_message : summary.verdict.reason;
  summary.timings.push_back({"final_state", phase.seconds()});
  if (!cut_short(summary.termination))
    result.final_correspondences = std::make_shared<const Problem::CorrespondenceState>(problem.correspondence_state());

  result.params = params;
  result.vertices = problem.evaluator().vertices();
  result.model_vertices = result.vertices;
  if (options.detail.enabled && summary.usable()) {
    phase.reset();
    // The final pairs above are the detail's first-pass pairs when the thresholds agree (default).
    const DetailFirstPass final_pairs{problem.pairs(), problem.correspondence_hints()};
    const bool same_pairs = options.detail.max_distance_mm == options.correspondences.max_distance_end_mm;
    const SurfaceDetail d =
        fit_surface_detail(result.vertices, model.rest.F, scan, options.correspondences, options.detail,
                           options.threads, same_pairs ? &final_pairs : nullptr);
    result.vertices = d.vertices;
    result.detail_offsets = d.offsets;
    summary.detail = {true, d.kept, d.mean_abs_mm, d.max_abs_mm};
    summary.timings.push_back({"surface_detail", phase.seconds()});
  }
}

// finish_fit's second part: the landmark checks and their warnings, on the final surface.
void finish_checks(const model::RiggedModel& model, const std::vector<LandmarkTarget>& landmarks,
                   const FitOptions& options, const PlacedCheck& placed, FitResult& result) {
  FitSummary& summary = result.summary;
  // Checked on the final surface (detail included): what the user sees.
  summary.landmark_checks =
      check_landmarks(model, result.vertices, result.model_vertices, result.params, landmarks, options, placed);
  for (const auto& c : summary.landmark_checks) {
    if (!c.flagged) continue;
    std::string why;
    if (c.predicted_distance_mm > c.predicted_tolerance_mm)
      why = fmt(c.predicted_distance_mm) + " mm from where the scan's anatomy and the other landmarks put it (tolerance " +
            fmt(c.predicted_tolerance_mm, 0);
    else if (c.distance_mm > c.tolerance_mm)
      why = fmt(c.distance_mm) + " mm from the fitted model's landmark (tolerance " + fmt(c.tolerance_mm, 0);
    else
      why = fmt(c.anatomy_distance_mm) + " mm from " + c.anatomy + " (tolerance " +
            fmt(c.anatomy_tolerance_mm, 0);
    summary.warnings.push_back("landmark '" + c.name + "' is " + why + " mm): check it" +
                               (c.factor < 1 ? "; it was down-weighted in the fit (weight x" + fmt(c.factor, 2) + ")"
                                             : ""));
  }
  for (const auto& [a, b] : exchanged_labels(landmarks, placed.predicted, options.landmark_check_mm))
    summary.warnings.push_back("the labels of landmarks '" + landmarks[a].name + "' and '" + landmarks[b].name +
                               "' look exchanged: each lies where the other one belongs; check the labels");
  result.landmarks = landmarks;
}

}  // namespace
}  // namespace breastfit::fit
