#pragma once
/// \file Landmark-free initialisation: where the template goes on a scan given in any frame
/// (rotated up to 180° about any axis, upside down, seen from behind, translated). Hypotheses for
/// the body frame come from the scan's shape (mesh/body_frame.h: least-spread antero-posterior
/// axis, mirror-symmetry plane) with every choice of sign and of which in-plane axis is the long
/// one; each is fitted coarse to fine (a short rigid+scale ICP for all, then the arms and a brief
/// pose fit for the best few) and scored both ways (template → scan and scan → template), the best
/// kept. The score margin to the best *different* orientation is the confidence.
#include <string>
#include <vector>

#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::fit {

/// One body-frame hypothesis after its coarse fit.
struct OrientationHypothesis {
  std::string name;               ///< which turn of the shape's body frame, e.g. "upside down"
  model::Similarity similarity;   ///< template → scan after the hypothesis' fit
  double score = 0;               ///< lower is better (mm): two-way robust residual + misses
  double forward_mae_mm = 0;      ///< template → scan, over kept pairs
  double forward_kept = 0;        ///< share of template vertices with a scan point near them
  double reverse_mae_mm = 0;      ///< scan samples → template, over kept pairs
  double reverse_kept = 0;        ///< share of scan samples with the template near them
  bool refined = false;           ///< got the arms and the brief pose fit
};

struct OrientationSearch {
  model::PoseParams params;                   ///< the best hypothesis: global similarity and arms
  std::vector<OrientationHypothesis> hypotheses;  ///< all, best first
  /// (score of the best hypothesis turned ≥ 45° away from the best − best score) / best score;
  /// large = unambiguous. 0 when two different orientations fit equally well.
  double margin = 0;
  std::string runner_up;                      ///< name of that hypothesis ("" when none)
  std::string body_frame;                     ///< how the shape's body frame was found
  double arm_abduction_deg[2] = {0, 0};       ///< R, L, from the vertical (template rest 24°)
  double width_to_height = 0;                 ///< the scan's extent across / along the body
  /// "arms hanging (standing)" or "arms abducted (supine, arm boards)": width_to_height ≥ 1.2;
  /// supine, the breasts start displaced sideways and towards the head (params.alpha).
  std::string arm_pose;
};

/// The template's initial placement on `scan` without landmarks (see the file comment).
/// Deterministic; leaves the scan's normal sign as set for the best hypothesis.
OrientationSearch search_orientation(const model::RiggedModel& model, ScanTarget& scan, const FitOptions& options);

/// Angle of the rotation taking a to b, degrees.
double rotation_angle_deg(const Quat& a, const Quat& b);

}  // namespace breastfit::fit
