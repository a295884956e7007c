#pragma once
/// \file A cohort on all cores of one machine (`breastfit batch`): every case registered into
/// its sub-directory of the output root by a pool of threads, then cohort.csv and cohort.html.
#include <filesystem>
#include <functional>
#include <vector>

#include "breastfit/cohort/case_record.h"
#include "breastfit/cohort/case_run.h"
#include "breastfit/cohort/cohort_case.h"

namespace breastfit::cohort {

struct BatchOptions {
  CaseRunOptions run;  ///< per case (template, fit options, force, report.html)
  int jobs = 1;        ///< cases registered at the same time (threads; >= 1; > 1: each fit on one thread unless run.fit.threads says otherwise)
};

/// Called after each case, from the worker that ran it but never concurrently: `done` cases of
/// `total` are finished, `record` is the one just finished.
using BatchProgress = std::function<void(int done, int total, const CaseRecord& record)>;

/// Runs every case (run_case: a failing case is recorded, the others go on; finished cases are
/// skipped unless options.run.force) and returns the records in case order. The template is
/// loaded once when options.run.model is null.
/// \throws InvalidInput for jobs < 1; IoError when `out_root` cannot be created or the default
///         template cannot be read
std::vector<CaseRecord> run_batch(const std::vector<CohortCase>& cases, const std::filesystem::path& out_root,
                                  const BatchOptions& options, const BatchProgress& progress = {});

/// Writes `out_root`/cohort.csv and `out_root`/cohort.html as one set (io::loose_file_set,
/// cohort.csv last): a reader never sees half a file, nor a table of another run than the page.
/// \throws IoError when a file cannot be written
void write_cohort_summary(const std::filesystem::path& out_root, const std::vector<CaseRecord>& records);

}  // namespace breastfit::cohort
