#pragma once
/// \file Landmarks given in the wrong frame or units. When the landmarks lie far from the scan
/// (median distance to its surface above `off_scan_mm`), the usual mistakes are tried: x and y
/// negated (3D Slicer's RAS read as LPS, or the reverse), a factor 1000 either way (metres read as
/// millimetres or the reverse), and both. If one of them puts the landmarks on the scan (median
/// within `on_scan_mm`), the mistake is named — diagnosed as such rather than as a failed fit.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/fit/scan_target.h"

namespace breastfit::pipeline {

struct LandmarkFrameDiagnosis {
  double median_distance_mm = 0;  ///< of the landmarks as given, to the scan surface
  std::string mistake;            ///< e.g. "x and y negated (RAS read as LPS, or the reverse)"
  double corrected_median_mm = 0; ///< with the mistake undone
};

/// nullopt when the landmarks lie on the scan, or when no usual mistake explains their distance.
/// Needs at least 3 landmarks (fewer: nullopt).
std::optional<LandmarkFrameDiagnosis> diagnose_landmark_frame(const std::vector<std::pair<std::string, Vec3>>& landmarks_mm,
                                                              const fit::ScanTarget& scan, double off_scan_mm = 30.0,
                                                              double on_scan_mm = 10.0);

}  // namespace breastfit::pipeline
