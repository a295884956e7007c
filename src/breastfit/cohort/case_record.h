#pragma once
/// \file One row of a cohort: how one case's registration went and its numbers (cohort.csv).
#include <optional>
#include <string>

namespace breastfit::cohort {

/// What happened to one case. The numbers come from the case's report.json (so a resumed case
/// gives the same row as the run that fitted it); they are nullopt when the case failed or the
/// report has no such number (e.g. no landmarks given, a contour missing).
struct CaseRecord {
  std::string name;            ///< the case's name (its output sub-directory)
  std::string scan;            ///< the scan file
  /// "ok" (usable fit, full output set), "not_usable" (the fit ran but did not come to lie on
  /// the scan; report.json only) or "failed" (bad input or a file error; no report.json).
  std::string status = "failed";
  bool resumed = false;        ///< read from a previous run's report.json instead of fitted now
  std::string message;         ///< why it failed / was not usable (empty when ok)
  std::optional<double> time_s;            ///< report.json time_s: scan in memory → fitted parameters
  std::optional<double> wall_s;            ///< this run's wall time for the case (read, fit, write); nullopt when resumed
  std::optional<int> iterations;           ///< solver iterations
  std::optional<double> surface_mae_mm;    ///< fitted surface → scan, mean (the paper's Table 1)
  std::optional<double> surface_max_mm;
  std::optional<double> landmark_mae_mm;   ///< fitted model landmarks → given landmarks, mean
  std::optional<double> landmark_max_mm;
  std::optional<double> volume_right_ml, volume_left_ml;  ///< breast volumes
  std::optional<double> volume_ratio;      ///< left / right
  std::optional<double> notch_to_nipple_right_mm, notch_to_nipple_left_mm;
  std::optional<double> nipple_to_imf_right_mm, nipple_to_imf_left_mm;
  std::optional<double> inter_nipple_mm;
  int warnings = 0;                        ///< number of warnings in report.json

  /// A finished case is skipped when a cohort is resumed: its report.json exists ("ok",
  /// "implausible" or "not_usable"); a failed case is tried again.
  bool finished() const { return status == "ok" || status == "implausible" || status == "not_usable"; }
};

}  // namespace breastfit::cohort
