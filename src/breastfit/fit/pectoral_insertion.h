#pragma once
/// \file The pectoral insertion found on the scan without its landmark: where the anterior
/// axillary fold (the lower border of pectoralis major, leaving the chest wall towards the arm)
/// meets the front of the upper arm.
///
/// Without a placed insertion the fit leaves it too medial (8–14 mm) and, arms hanging, too low
/// (about 14 mm): nothing on the smooth front of the shoulder holds the template's point. On the
/// scan, a slice across the upper arm below the fold shows two bulges seen from the front — the
/// chest (breast, pectoral) and the arm — with a crease between them (the gap of the axilla, seen
/// from the front); above the fold's lower border the fold bridges them and the crease is gone.
/// The detector walks slices across the arm from the shoulder towards the elbow and takes the first
/// one whose crease is at least `min_crease_mm` deep; the insertion is the arm's most anterior
/// point in that slice (the truth's skin normal there faces straight forward on the 14 benchmark
/// torsos). It refuses (nullopt) when no slice shows such a crease (arms abducted on arm boards:
/// the arm leaves the chest sideways, no crease faces the front), when the scan is missing, or
/// when the point found lies farther than `max_shift_mm` from the fitted one.
///
/// Used by `breastfit landmarks` (pipeline/detect_landmarks.h) to refine the fitted insertion on the
/// scan; it is not held in the fit (held from the shape stage on, it moved the arm and shoulder with
/// it and cost 0.1 mm of landmark MAE on hold-out torsos: docs/REGISTRATION.md).
#include <optional>
#include <vector>

#include <string>

#include "breastfit/core/types.h"
#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::fit {

/// The slices' sampling and the crease they must show.
struct PectoralInsertionOptions {
  double bin_mm = 3.0;           ///< slice thickness along the arm and bin width across it
  double proximal_mm = 40.0;     ///< the first slice lies this far towards the shoulder from the fitted point
  double distal_mm = 50.0;       ///< the last this far towards the elbow
  double across_mm = 60.0;       ///< the profile's half-width across the arm, centred on the fitted point
  double max_behind_mm = 60.0;   ///< scan farther behind the fitted point is ignored (the back)
  double min_crease_mm = 8.0;    ///< depth of the crease between chest and arm, seen from the front
  double max_shift_mm = 35.0;    ///< a point farther than this from the fitted one = refused
  /// The arm must hang: at most this far from the body's downward axis (arms hanging 8–35°,
  /// on arm boards 65–95° on the benchmark's torsos).
  double max_abduction_deg = 50.0;
};

/// The pectoral insertion on the scan, or nullopt when unsure.
/// \param scan_vertices the scan (mm)
/// \param fitted the fitted model's insertion (the slices' centre)
/// \param arm_axis the upper arm's axis, pointing from the shoulder towards the elbow (unit)
/// \param up the body's superior axis, \param front its anterior axis (unit)
/// \param chest a point on the chest on the same side (e.g. the nipple): gives the side of the
///        profile that is the chest
std::optional<Vec3> pectoral_insertion_on_scan(const Points& scan_vertices, const Vec3& fitted, const Vec3& arm_axis,
                                               const Vec3& up, const Vec3& front, const Vec3& chest,
                                               const PectoralInsertionOptions& options = {});

/// The upper arm's axis on a posed model, from the shoulder towards the elbow: the main axis of the
/// vertices its bone mostly moves (`upper_arm_R` / `upper_arm_L`), pointing away from the acromion.
/// nullopt when the model has no such bone or landmark.
/// \param V the posed vertices, \param params their pose (for the landmark's position)
/// \param side "R" or "L"
std::optional<Vec3> upper_arm_axis(const model::RiggedModel& model, const Points& V, const model::PoseParams& params,
                                   const std::string& side);

/// The vertices upper_arm_axis reads for `side`, ascending: its arm's and its acromion's triangle's
/// corners. Posing only these (model::PoseEvaluator::pose_rows) gives the same axis, bit for bit, as
/// posing the whole mesh. Empty when the model has no such bone or landmark.
std::vector<Index> upper_arm_axis_rows(const model::RiggedModel& model, const std::string& side);

}  // namespace breastfit::fit
