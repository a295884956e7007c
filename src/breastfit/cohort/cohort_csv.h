#pragma once
/// \file cohort.csv: one row per case (status, times, surface and landmark errors, breast
/// volumes and measurements, warnings count), in case order.
#include <string>
#include <vector>

#include "breastfit/cohort/case_record.h"

namespace breastfit::cohort {

/// The column names, in order.
std::vector<std::string> cohort_csv_columns();

/// The CSV text: a header line, then one line per record; empty fields for missing numbers;
/// numbers with 6 significant digits (times 4 decimals); text fields quoted when needed (RFC 4180).
std::string format_cohort_csv(const std::vector<CaseRecord>& records);

}  // namespace breastfit::cohort
