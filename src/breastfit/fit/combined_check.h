#pragma once
/// \file Two weak signals that agree: a landmark whose prediction (landmark_prediction.h) and own
/// anatomical check (the breast's tip, the midline notch, the pair's mirror image, the insertion's
/// arm) both moved part of their tolerance is flagged, though neither alone is beyond it.
///
/// A landmark walked 20 mm along the skin often leaves each check at 0.6–0.9 of its tolerance,
/// where the landmarks as given also reach now and then — but rarely both at once. The statistic is
/// r_p² + r_a², the squared ratios of the prediction's and the anatomy's distances to their
/// tolerances; the threshold is per landmark, about 1.1–1.6× the largest value of the landmarks as
/// given on the 14 benchmark and 16 generated validation cases and on the template-made synthetic
/// torsos of the CI trials (seeds 23 standing, 22 supine) — docs/REGISTRATION.md, session 13:
/// notch 0.90 (as given at most 0.55 bench, 0.82 synthetic), acromia 0.80 (0.67), mid-axillary
/// points 1.0 (0.84), pectoral insertions 1.0 (0.90), nipples 0.85 (0.61 bench, 0.74 synthetic),
/// lowest breast points 0.95 (0.85). The xiphoid has no anatomical check of this kind.
///
/// Session 16: a bilateral pair within its tolerance also gives its asymmetry to the member it does
/// not blame (bilateral_check.h unblamed_member), with the same thresholds — as given that member's
/// r_p² + r_a² reaches 0.87 (lowest breast points), 0.76 (acromia) and 0.72 (mid-axillary points)
/// on the benchmark and validation cases —; and the pectoral insertion's arm check, tightened along
/// the sternum (pectoral_check.h), reaches 0.93 as given.
#include <optional>
#include <string>

namespace breastfit::fit {

/// The threshold on r_p² + r_a² of the landmark named `name`; nullopt for one not checked this way.
std::optional<double> combined_check_threshold(const std::string& name);

/// The combined check expressed on the anatomical distance: the anatomy's tolerance lowered by how
/// far the prediction already moved, `anatomy_tolerance_mm` · √(max(threshold − r_p², 0)); the
/// landmark is flagged when its anatomical distance exceeds it. nullopt for a landmark not checked
/// this way. \param predicted_ratio r_p (prediction distance / its tolerance)
std::optional<double> combined_anatomy_tolerance_mm(const std::string& name, double predicted_ratio,
                                                    double anatomy_tolerance_mm);

}  // namespace breastfit::fit
