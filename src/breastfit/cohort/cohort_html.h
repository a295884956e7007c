#pragma once
/// \file cohort.html: a cohort's summary for a reader — counts, distributions of the errors,
/// times and breast volumes (inline SVG histograms, no external resources), the outliers, the
/// failed and not-usable cases with their reasons, and every case's row linked to its report.
#include <string>
#include <vector>

#include "breastfit/cohort/case_record.h"

namespace breastfit::cohort {

/// A value of a case that lies far from the cohort: robust z = (x − median) / (1.4826 · MAD) > 3.
struct Outlier {
  std::string name;    ///< the case
  std::string metric;  ///< e.g. "surface_mae_mm"
  double value = 0;
  double robust_z = 0;
};

/// The outliers of the "ok" cases for the surface and landmark errors, the time and the volumes,
/// ordered by metric, then by decreasing robust z. A metric with fewer than 4 values, or with a
/// MAD of zero, has none.
std::vector<Outlier> find_outliers(const std::vector<CaseRecord>& records);

/// The whole page (self-contained HTML5).
std::string cohort_html(const std::vector<CaseRecord>& records);

}  // namespace breastfit::cohort
