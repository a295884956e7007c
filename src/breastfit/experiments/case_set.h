#pragma once
/// \file A directory of cases in the bench layout (the bench's visible cases, or cases made by
/// `breastfit synth`): each case is a folder with scan.ply, landmarks.mrk.json and, optionally,
/// truth/. Loads one case at a time: scan, input landmarks (in mm), pose, truth.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/experiments/case_truth.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/mesh/units.h"

namespace breastfit::experiments {

/// One case in memory, ready to be registered many times.
struct EvalCase {
  std::string id;                      ///< the folder's name
  std::filesystem::path dir;
  std::string pose = "unknown";        ///< "standing", "supine" or "unknown"
  TriangleMesh scan;                   ///< as read (file units, scanner frame)
  mesh::Units units = mesh::Units::Millimetres;  ///< the scan's units (detected, or truth/meta.json)
  double to_mm = 1.0;                  ///< file units → mm
  std::optional<LandmarkSet> landmarks;  ///< as read (nullopt: the case has no landmarks.mrk.json)
  std::vector<std::pair<std::string, Vec3>> landmarks_mm;  ///< the same in mm (empty when none)
  std::optional<CaseTruth> truth;      ///< nullopt when the case has no truth/
};

/// The case folders under `dir` (folders holding scan.ply, sorted by name), or `dir` itself
/// when it holds scan.ply. `only` (when non-empty) keeps the cases with these ids, in the
/// order of the directory. \throws IoError when `dir` is not a directory, holds no case, or an
/// id of `only` is not found.
std::vector<std::filesystem::path> find_case_dirs(const std::filesystem::path& dir,
                                                  const std::vector<std::string>& only = {});

/// The pose of a case: truth/meta.json's "pose" when present, else "supine" / "standing" when
/// the id contains that word, else "unknown".
std::string case_pose(const std::filesystem::path& case_dir);

/// Loads a case (scan, landmarks, pose, truth).
/// \throws IoError / InvalidInput for unreadable or invalid files (naming them).
EvalCase load_case(const std::filesystem::path& case_dir);

}  // namespace breastfit::experiments
