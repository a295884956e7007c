#pragma once
/// \file Initial placement of the template in the scan's frame: a similarity from landmarks
/// (Umeyama with scale), detection of left/right-swapped labels, and the arms' abduction. The
/// landmark-free placement is orientation_search.h.
#include <array>
#include <string>
#include <vector>

#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/landmark_target.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::fit {

/// Least-squares similarity dst ≈ s R src + t (Umeyama 1991). src, dst: n by 3, n ≥ 3, not collinear.
/// \throws InvalidInput when fewer than 3 points or they are (nearly) collinear.
model::Similarity umeyama_similarity(const Points& src, const Points& dst);

struct LandmarkInitialization {
  model::Similarity similarity;
  double rms_mm = 0.0;            ///< RMS landmark residual after the similarity
  bool swapped = false;           ///< the input's _R/_L labels were swapped and have been corrected
  double swapped_rms_mm = 0.0;    ///< RMS with the other labelling (for the report)
};

/// Similarity taking the rest template's landmarks onto `targets`. When swapping every _R/_L label
/// fits far better (RMS < 0.6× and the unswapped RMS > 15 mm), the targets are relabelled in place
/// and `swapped` is set. \pre targets.size() ≥ 3.
LandmarkInitialization initialize_from_landmarks(const model::RiggedModel& model,
                                                 std::vector<LandmarkTarget>& targets);

/// Abduction of each upper arm (bones "upper_arm_R"/"upper_arm_L", about the antero-posterior
/// axis through the shoulder joint) chosen by a coarse search against the scan: arms go from
/// hanging (standing) to 90° on arm boards (supine), further than closest points can pull them.
/// Bones that are missing are skipped. \pre params.global already places the template on the scan.
/// The angles are scored on `threads` threads (≤ 0: all cores); the choice does not depend on it.
/// `two_way`: the scan's samples beyond each shoulder must also lie near the arm (without
/// landmarks an arm lowered onto the chest wall lies on the scan too).
/// \returns the angle each arm was raised by (R, L; degrees, negative = lowered; 0 when missing).
std::array<double, 2> initialize_arms(const model::RiggedModel& model, const ScanTarget& scan, model::PoseParams& params,
                                      bool two_way = false, int threads = 0);

}  // namespace breastfit::fit
