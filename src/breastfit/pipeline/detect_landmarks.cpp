#include "breastfit/pipeline/detect_landmarks.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "breastfit/core/errors.h"
#include "breastfit/fit/nipple_apex.h"
#include "breastfit/fit/pectoral_insertion.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/fit/shoulder_landmarks.h"
#include "breastfit/fit/sliding_landmarks.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/model/template_library.h"

namespace breastfit::pipeline {
namespace {

constexpr double kSupportScaleMm = 10.0;  // snapping this far halves the confidence by e

// The orientation's share of the confidence: 1 from a margin of 0.5 (the runner-up scores 50 %
// worse), falling linearly to 0 at no margin.
double orientation_confidence(const fit::OrientationSummary& o) {
  if (!o.searched || !std::isfinite(o.margin)) return 1.0;
  return std::clamp(o.margin / 0.5, 0.0, 1.0);
}

// A fitted landmark's position by name.
std::optional<Vec3> fitted_landmark(const model::RiggedModel& model, const fit::FitResult& fit, const std::string& name) {
  const auto idx = model.landmark_index(name);
  if (!idx) return std::nullopt;
  return fit::model_landmark_position(model, *idx, fit.model_vertices, fit.params);
}

// The fitted sternum's frame on one side ("R" or "L"): up along the sternum, front level from the
// nipples; nullopt without those landmarks.
std::optional<fit::SternumFrame> sternum_frame(const model::RiggedModel& model, const fit::FitResult& fit,
                                               const std::string& side) {
  const auto notch = fitted_landmark(model, fit, "sternal_notch"), xiphoid = fitted_landmark(model, fit, "xiphoid");
  const auto right = fitted_landmark(model, fit, "nipple_R"), left = fitted_landmark(model, fit, "nipple_L");
  if (!notch || !xiphoid || !right || !left) return std::nullopt;
  return fit::sternum_frame(*notch, *xiphoid, *right, *left, side.at(0));
}

// The pectoral insertion refined on the scan by its definition (fit/pectoral_insertion.h): the front
// of the arm where the anterior axillary fold leaves it, searched from the fitted one; nullopt
// when the detector is unsure (no crease, holes) or the fit lacks the landmarks, and not tried
// unless the orientation search found the arms hanging (standing: on arm boards the arm leaves the
// chest sideways; the arm-axis check alone let it move 5 of the 32 insertions of 16 generated
// supine torsos, each farther from the truth).
std::optional<Vec3> pectoral_insertion_refined(const model::RiggedModel& model, const fit::FitResult& fit,
                                               const std::string& name, const fit::ScanTarget& scan) {
  if (fit.summary.orientation.arm_pose.rfind("arms hanging", 0) != 0) return std::nullopt;
  const std::string side = name.substr(name.size() - 1);
  const auto frame = sternum_frame(model, fit, side);
  const auto nipple = fitted_landmark(model, fit, "nipple_" + side);
  const auto fitted = fitted_landmark(model, fit, name);
  const auto arm = fit::upper_arm_axis(model, fit.model_vertices, fit.params, side);
  if (!frame || !nipple || !fitted || !arm) return std::nullopt;
  return fit::pectoral_insertion_on_scan(scan.mesh().V, *fitted, *arm, frame->up, frame->front, *nipple);
}

// The acromion, the mid-axillary point and the pectoral insertion refined on the scan by the
// sternum's proportions (fit/shoulder_landmarks.h), only with the arms on boards (the orientation
// search's arm pose, and the scan's arms reaching out sideways): there the template's skin over the shoulder and
// the side of the chest follows the abducted arm.
std::optional<Vec3> shoulder_landmark_refined(const model::RiggedModel& model, const fit::FitResult& fit,
                                              const std::string& name, const fit::ScanTarget& scan) {
  const bool acromion = name.rfind("acromion_", 0) == 0, pectoral = name.rfind("pectoral_insertion_", 0) == 0;
  if (!acromion && !pectoral && name.rfind("midaxillary_", 0) != 0) return std::nullopt;
  if (fit.summary.orientation.arm_pose.rfind("arms abducted", 0) != 0) return std::nullopt;
  const std::string side = name.substr(name.size() - 1);
  const auto frame = sternum_frame(model, fit, side);
  const auto fitted = fitted_landmark(model, fit, name);
  if (!frame || !fitted || !fit::arms_abducted_on_scan(scan.mesh().V, *frame)) return std::nullopt;
  const Points& V = scan.mesh().V;
  return acromion ? fit::acromion_on_scan(V, *fitted, *frame)
         : pectoral ? fit::abducted_pectoral_insertion_on_scan(V, *frame)
                    : fit::midaxillary_on_scan(V, *fitted, *frame);
}

// The nipple on the scan at the final fit: the breast's apex along its level forward axis
// (fit/nipple_apex.h; N: the fitted model's vertex normals); nullopt without the sternum's
// landmarks or scan around the nipple.
std::optional<Vec3> nipple_refined(const model::RiggedModel& model, const fit::FitResult& fit, const Points& N,
                                   const std::string& name, const fit::ScanTarget& scan) {
  const auto notch = fitted_landmark(model, fit, "sternal_notch"), xiphoid = fitted_landmark(model, fit, "xiphoid");
  const auto fitted = fitted_landmark(model, fit, name);
  if (!notch || !xiphoid || !fitted) return std::nullopt;
  return fit::nipple_apex_on_scan(scan.mesh().V, fit.model_vertices, N, *fitted, (*notch - *xiphoid).normalized());
}

// The landmark-free fit's landmarks snapped onto the scan (`scan`: its closest-point index), the
// nipples (the breast's apex), the pectoral insertions and, arms on boards, the acromia and the
// mid-axillary points refined on the scan where the detectors are sure.
DetectedLandmarks landmarks_on_scan(const model::RiggedModel& model, const std::string& scan_name,
                                    RegisterResult registration, const fit::ScanTarget& scan) {
  DetectedLandmarks out;
  out.registration = std::move(registration);
  const RegisterResult& r = out.registration;
  if (!r.usable()) throw InvalidInput(scan_name + ": " + r.fit.summary.verdict.reason);
  const double oriented = orientation_confidence(r.fit.summary.orientation);
  const Points normals = mesh::vertex_normals(r.fit.model_vertices, model.rest.F);
  for (const auto& p : r.model_landmarks_mm.points) {
    DetectedLandmark d;
    d.name = p.name;
    const fit::ScanMatch m = scan.closest(p.position);
    const double gap = std::sqrt(m.sq_dist);
    d.position_mm = m.point;
    d.confidence = oriented * std::exp(-gap / kSupportScaleMm);
    if (p.name.rfind("pectoral_insertion_", 0) == 0) {
      if (const auto refined = pectoral_insertion_refined(model, r.fit, p.name, scan)) {
        d.position_mm = *refined;  // a scan vertex
        d.method = "anterior axillary fold on the scan";
        // Its height by the sternum's proportions (fit/shoulder_landmarks.h): the first slice
        // showing the crease lies below the fold's border.
        if (const auto frame = sternum_frame(model, r.fit, p.name.substr(p.name.size() - 1)))
          if (const auto level = fit::hanging_pectoral_insertion_on_scan(scan.mesh().V, *refined, *frame)) {
            d.position_mm = *level;
            d.method = "anterior axillary fold on the scan, at the sternum's proportion";
          }
        out.landmarks.push_back(d);
        continue;
      }
    }
    if (const auto refined = shoulder_landmark_refined(model, r.fit, p.name, scan)) {
      d.position_mm = *refined;  // a scan vertex
      d.method = "sternum's proportions on the scan";
      out.landmarks.push_back(d);
      continue;
    }
    // Held on the scan's anatomy in the fit: the nipples, the notch and the folds (the shoulder's
    // landmarks held there are refined above, else written as fitted).
    const auto& held = r.fit.summary.anatomical_landmark_names;
    const bool nipple = p.name == "nipple_R" || p.name == "nipple_L";
    const bool anatomical = std::find(held.begin(), held.end(), p.name) != held.end() &&
                            (nipple || p.name == "sternal_notch" || p.name.rfind("lowest_breast_", 0) == 0);
    if (nipple && anatomical)
      if (const auto apex = nipple_refined(model, r.fit, normals, p.name, scan)) d.position_mm = scan.closest(*apex).point;
    d.method = !anatomical                  ? "fitted template, snapped to the scan"
               : nipple                     ? "breast tip on the scan"
               : p.name == "sternal_notch" ? "jugular notch on the scan"
                                            : "breast fold on the scan";
    out.landmarks.push_back(d);
  }
  return out;
}

void without_landmarks(RegisterRequest& request) {
  request.landmarks.reset();
  request.options.use_landmarks = false;
}

}  // namespace

// The request's template, loaded here when it is the default (one load serves the fit and the
// refinement).
std::shared_ptr<const model::RiggedModel> template_of(RegisterRequest& request) {
  if (!request.model) request.model = std::make_shared<const model::RiggedModel>(model::load_default_template());
  return request.model;
}

DetectedLandmarks detect_landmarks(RegisterRequest request) {
  without_landmarks(request);
  const auto model = template_of(request);
  RegisterResult r = register_scan(request);
  if (!r.usable()) throw InvalidInput(request.scan_name + ": " + r.fit.summary.verdict.reason);
  const fit::ScanTarget scan(r.scan.mesh_mm, 0);
  return landmarks_on_scan(*model, request.scan_name, std::move(r), scan);
}

DetectedLandmarks detect_landmarks(RegisterRequest request, PreparedTarget& target,
                                   const fit::IterationCallback& on_iteration) {
  without_landmarks(request);
  const auto model = template_of(request);
  RegisterResult r = register_prepared(request, target, on_iteration);
  return landmarks_on_scan(*model, target.scan_name, std::move(r), *target.target);
}

Markups to_markups(const std::vector<DetectedLandmark>& landmarks) {
  Markups m;
  for (const auto& d : landmarks) m.points.push_back({d.name, d.position_mm});
  return m;
}

}  // namespace breastfit::pipeline
