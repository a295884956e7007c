#pragma once
/// \file What one CASE of a cohort is (`breastfit batch CASES...`, `python3 -m breastfit.cohort`):
/// a scan, its optional landmarks and the name of its output sub-directory.
///
/// A CASE argument is one of:
///  - a scan file (.ply .obj .stl): the case is named by the file's stem (`p001.ply` → `p001`);
///    its landmarks are the sibling file with the same stem and a landmark extension, looked for
///    in the order .mrk.json, .json, .csv, .fcsv (`p001.mrk.json`), none when there is none;
///  - a case directory holding `scan.ply` (or `scan.obj`, `scan.stl`), the layout `breastfit
///    synth` writes: named by the directory, landmarks `landmarks.mrk.json` (or .json, .csv,
///    .fcsv) beside the scan when present;
///  - a directory of cases: a directory without a scan file whose sub-directories are case
///    directories (sorted by name; sub-directories without a scan are ignored).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace breastfit::cohort {

struct CohortCase {
  std::string name;                                ///< output sub-directory name, unique in a cohort
  std::filesystem::path scan;                      ///< the scan file
  std::optional<std::filesystem::path> landmarks;  ///< its landmark file, when there is one
};

/// The case named by one CASE argument (see the file comment); a directory of cases gives several.
/// \throws IoError naming the argument when it does not exist, is neither a scan file nor a
///         directory, or is a directory holding no case
std::vector<CohortCase> resolve_case_argument(const std::filesystem::path& argument);

/// The cases of every argument, in argument order.
/// \throws IoError as resolve_case_argument; InvalidInput when no argument is given or two cases
///         have the same name (naming both scans)
std::vector<CohortCase> resolve_cases(const std::vector<std::filesystem::path>& arguments);

}  // namespace breastfit::cohort
