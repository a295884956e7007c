#pragma once
/// \file Documented exit codes of the breastfit executable.
namespace breastfit::cli {
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;       ///< unexpected internal error
inline constexpr int kExitUsage = 2;         ///< bad command line
inline constexpr int kExitInvalidInput = 3;  ///< input data rejected (bad values, wrong landmarks, ...)
inline constexpr int kExitIoError = 4;       ///< a file could not be read or written
inline constexpr int kExitNotConverged = 5;  ///< the registration did not converge to a usable fit
inline constexpr int kExitCasesFailed = 6;   ///< batch: a case failed or was not usable (the others were done)
/// register/demo: the fit is usable but implausible (metrics/plausibility.h): every output is
/// written, report.json has "status": "implausible" and the problems
inline constexpr int kExitImplausible = 7;
}  // namespace breastfit::cli
