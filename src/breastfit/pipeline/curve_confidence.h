#pragma once
/// \file A plain-language confidence for one transferred drawing, from how much of it the scan
/// supports and how far the transfer had to move it (the local fit residual along it): what the
/// registration report shows the surgeon next to each curve.
#include <string>
#include <string_view>

#include "breastfit/transfer/drawing_transfer.h"

namespace breastfit::pipeline {

enum class CurveConfidence {
  High,   ///< on the scan almost everywhere and the fitted model follows the scan closely there
  Check,  ///< usable, but look at it: parts over holes or a looser fit along it
  Low,    ///< mostly not on the scan, or the model is far from the scan along it
};

/// Thresholds of the rule (see curve_confidence).
inline constexpr double kHighSupportedFraction = 0.9;   ///< high: at least this fraction on the scan
inline constexpr double kHighMeanDistanceMm = 2.0;      ///< high: mean model-to-scan at most this, mm
inline constexpr double kCheckSupportedFraction = 0.5;  ///< check: at least this fraction on the scan
inline constexpr double kCheckMeanDistanceMm = 5.0;     ///< check: mean model-to-scan at most this, mm

/// High when supported_fraction >= 0.9 and mean_model_to_scan_mm <= 2 mm; else Check when
/// supported_fraction >= 0.5 and mean_model_to_scan_mm <= 5 mm; else Low.
CurveConfidence curve_confidence(const transfer::TransferredCurve& curve);

/// "high", "check", "low".
std::string_view confidence_name(CurveConfidence c);

/// The rule in one sentence, for readers of the report.
std::string curve_confidence_rule();

}  // namespace breastfit::pipeline
