#pragma once
/// \file Registering one case of a cohort into its output sub-directory, resumably, never
/// throwing for a bad case: what `breastfit batch` and the Dask cohort (python/breastfit/cohort.py)
/// run per case.
#include <filesystem>
#include <memory>
#include <optional>

#include "breastfit/cohort/case_record.h"
#include "breastfit/cohort/cohort_case.h"
#include "breastfit/fit/fit_options.h"
#include "breastfit/mesh/units.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::cohort {

struct CaseRunOptions {
  std::shared_ptr<const model::RiggedModel> model;  ///< the template (nullptr: the shipped default, loaded per case)
  fit::FitOptions fit;                              ///< fit options for every case
  std::optional<mesh::Units> units;                 ///< forced scan units (nullopt: detect per scan)
  bool ignore_landmarks = false;  ///< do not read the cases' landmark files (landmark-free fits)
  bool force = false;        ///< fit again even when the case's report.json exists
  bool report_html = true;   ///< write each case's report.html
  /// For report.json's provenance: the template's file (empty: the shipped default's path when
  /// `model` is nullptr, none otherwise) and the command line that started the cohort.
  std::filesystem::path template_path;
  std::string command_line;
};

/// The output sub-directory of a case: `out_root / name`.
std::filesystem::path case_output_dir(const std::filesystem::path& out_root, const CohortCase& c);

/// The record of a previous run when its output directory holds a report.json that parses
/// (resumed = true), nullopt otherwise.
std::optional<CaseRecord> finished_record(const std::filesystem::path& out_root, const CohortCase& c);

/// Registers `c` and writes the register output set (pipeline/register_outputs.h) into
/// case_output_dir(out_root, c) — replacing what a previous, unfinished run left there — or,
/// without `force`, returns the finished record of a previous run untouched. A bad scan or
/// landmark file, or an output that cannot be written, gives a record with status "failed" and
/// the error's one-line message; a fit that is not usable writes its report.json only (status
/// "not_usable"). Throws nothing but std::bad_alloc.
CaseRecord run_case(const CohortCase& c, const std::filesystem::path& out_root, const CaseRunOptions& options);

}  // namespace breastfit::cohort
