#include "breastfit/pipeline/curve_confidence.h"

#include <cmath>
#include <cstdio>

namespace breastfit::pipeline {

CurveConfidence curve_confidence(const transfer::TransferredCurve& c) {
  const double f = c.supported_fraction, d = c.mean_model_to_scan_mm;
  if (!std::isfinite(f) || !std::isfinite(d)) return CurveConfidence::Low;
  if (f >= kHighSupportedFraction && d <= kHighMeanDistanceMm) return CurveConfidence::High;
  if (f >= kCheckSupportedFraction && d <= kCheckMeanDistanceMm) return CurveConfidence::Check;
  return CurveConfidence::Low;
}

std::string_view confidence_name(CurveConfidence c) {
  switch (c) {
    case CurveConfidence::High: return "high";
    case CurveConfidence::Check: return "check";
    case CurveConfidence::Low: return "low";
  }
  return "low";
}

std::string curve_confidence_rule() {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "high: at least %.0f %% of the curve lies on the scan and the fitted model is on average at "
                "most %.0f mm from the scan along it; check: at least %.0f %% on the scan and at most %.0f mm; "
                "low: otherwise.",
                100 * kHighSupportedFraction, kHighMeanDistanceMm, 100 * kCheckSupportedFraction,
                kCheckMeanDistanceMm);
  return buf;
}

}  // namespace breastfit::pipeline
