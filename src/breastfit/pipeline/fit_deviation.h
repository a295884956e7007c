#pragma once
/// \file How far one registration's geometry lies from another's of the same scan and template:
/// e.g. the workstation's warm re-fit against a full (cold) fit with the same landmarks. The
/// fitted surface is compared vertex by vertex (same template), the template's landmarks point by
/// point, and each transferred drawing point to the other fit's drawing of the same name (point to
/// polyline: the curves are resampled, so their points need not pair up).
#include "breastfit/pipeline/register_scan.h"

namespace breastfit::pipeline {

struct FitDeviation {
  double surface_median_mm = 0;   ///< median over the fitted vertices of |a − b|
  double surface_max_mm = 0;      ///< largest vertex distance
  double landmarks_max_mm = 0;    ///< largest distance between the fitted template's landmarks
  double drawings_max_mm = 0;     ///< largest distance of a drawing point to the other's same drawing (both ways)
};

/// The deviation between `a` and `b`, fits of the same template (the landmarks and drawings
/// present in both are compared). \throws InvalidInput when their fitted vertex counts differ.
FitDeviation fit_deviation(const RegisterResult& a, const RegisterResult& b);

}  // namespace breastfit::pipeline
