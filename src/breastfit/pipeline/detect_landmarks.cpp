#include "breastfit/pipeline/detect_landmarks.h"

#include <algorithm>
#include <cmath>

#include "breastfit/core/errors.h"
#include "breastfit/fit/scan_target.h"

namespace breastfit::pipeline {
namespace {

constexpr double kSupportScaleMm = 10.0;  // snapping this far halves the confidence by e

// The orientation's share of the confidence: 1 from a margin of 0.5 (the runner-up scores 50 %
// worse), falling linearly to 0 at no margin.
double orientation_confidence(const fit::OrientationSummary& o) {
  if (!o.searched || !std::isfinite(o.margin)) return 1.0;
  return std::clamp(o.margin / 0.5, 0.0, 1.0);
}

// The landmark-free fit's landmarks snapped onto the scan (`scan`: its closest-point index).
DetectedLandmarks landmarks_on_scan(const std::string& scan_name, RegisterResult registration,
                                    const fit::ScanTarget& scan) {
  DetectedLandmarks out;
  out.registration = std::move(registration);
  const RegisterResult& r = out.registration;
  if (!r.usable()) throw InvalidInput(scan_name + ": " + r.fit.summary.verdict.reason);
  const double oriented = orientation_confidence(r.fit.summary.orientation);
  for (const auto& p : r.model_landmarks_mm.points) {
    DetectedLandmark d;
    d.name = p.name;
    const fit::ScanMatch m = scan.closest(p.position);
    const double gap = std::sqrt(m.sq_dist);
    d.position_mm = m.point;
    d.confidence = oriented * std::exp(-gap / kSupportScaleMm);
    const auto& held = r.fit.summary.anatomical_landmark_names;
    const bool anatomical = std::find(held.begin(), held.end(), p.name) != held.end();
    const bool nipple = p.name == "nipple_R" || p.name == "nipple_L";
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

DetectedLandmarks detect_landmarks(RegisterRequest request) {
  without_landmarks(request);
  RegisterResult r = register_scan(request);
  if (!r.usable()) throw InvalidInput(request.scan_name + ": " + r.fit.summary.verdict.reason);
  const fit::ScanTarget scan(r.scan.mesh_mm, 0);
  return landmarks_on_scan(request.scan_name, std::move(r), scan);
}

DetectedLandmarks detect_landmarks(RegisterRequest request, PreparedTarget& target,
                                   const fit::IterationCallback& on_iteration) {
  without_landmarks(request);
  RegisterResult r = register_prepared(request, target, on_iteration);
  return landmarks_on_scan(target.scan_name, std::move(r), *target.target);
}

Markups to_markups(const std::vector<DetectedLandmark>& landmarks) {
  Markups m;
  for (const auto& d : landmarks) m.points.push_back({d.name, d.position_mm});
  return m;
}

}  // namespace breastfit::pipeline
