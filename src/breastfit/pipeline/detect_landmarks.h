#pragma once
/// \file The 12 landmarks found on a scan without any given (`breastfit landmarks`): a landmark-free
/// registration (fit/orientation_search.h; the nipples held at the breast tips found on the scan),
/// then each of the fitted template's landmarks snapped onto the scan, with a confidence; the
/// nipples refined to the breast's apex on the scan (fit/nipple_apex.h), the pectoral insertions,
/// arms hanging, by their definition on the scan (fit/pectoral_insertion.h), and with the arms on
/// boards the acromia, mid-axillary points and pectoral insertions by the sternum's proportions
/// (fit/shoulder_landmarks.h). The result is a starting point a person checks and corrects before
/// `register --landmarks`.
#include <string>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/pipeline/register_scan.h"

namespace breastfit::pipeline {

struct DetectedLandmark {
  std::string name;
  Vec3 position_mm = Vec3::Zero();  ///< on the scan, scanner frame, mm
  /// In [0, 1]: the orientation's confidence (score margin) times the scan's support at the point
  /// (exp(−distance from the fitted landmark to the scan / 10 mm)).
  double confidence = 0;
  /// "fitted template, snapped to the scan", or the anatomy that held or refined it ("breast tip on
  /// the scan", "jugular notch on the scan", "breast fold on the scan", "anterior axillary fold on the
  /// scan": the pectoral insertion, fit/pectoral_insertion.h, "..., at the sternum's proportion" when
  /// its height is then taken from the sternum; "sternum's proportions on the scan":
  /// fit/shoulder_landmarks.h)
  std::string method;
};

struct DetectedLandmarks {
  std::vector<DetectedLandmark> landmarks;  ///< the template's landmarks, in its order
  RegisterResult registration;              ///< the landmark-free fit they come from
};

/// Runs `request` without landmarks (request.landmarks and use_landmarks are ignored) and returns
/// the template's landmarks on the scan. \throws as register_scan; InvalidInput when the fit is not
/// usable (its verdict).
DetectedLandmarks detect_landmarks(RegisterRequest request);

/// detect_landmarks on a scan prepared once (the workstation's open scan: its index is not
/// rebuilt; `request.scan` and `request.units` are not used). `on_iteration` sees every solver
/// iteration and may abort (the fit is then not usable: InvalidInput). One fit per target at a
/// time (register_prepared).
DetectedLandmarks detect_landmarks(RegisterRequest request, PreparedTarget& target,
                                   const fit::IterationCallback& on_iteration = {});

/// The detected landmarks as markups (mm), for io::write_markups.
Markups to_markups(const std::vector<DetectedLandmark>& landmarks);

}  // namespace breastfit::pipeline
