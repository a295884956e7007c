#pragma once
/// \file The ground truth of a case in the bench layout (docs/SYNTH.md "Case layout", written by
/// `breastfit synth` too): truth/surface.ply, truth/landmarks.json, truth/curves.json and the
/// units in truth/meta.json. Only experiments read it; a registration never does.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "breastfit/mesh/landmarks.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::experiments {

/// Truth of one case, in millimetres, in the scanner frame.
struct CaseTruth {
  TriangleMesh surface_mm;             ///< clean cropped subject surface
  std::vector<NamedPoint> landmarks_mm;  ///< exact landmarks
  std::vector<Curve> curves_mm;        ///< exact drawings (breast_contour_R/L, imf_R/L, sternum)
};

/// The units the case's truth/meta.json declares ("mm" or "m"), or nullopt when it has no
/// meta.json or no "units" key. \throws IoError for an unreadable or malformed meta.json or
/// units other than "mm" / "m".
std::optional<std::string> read_truth_units(const std::filesystem::path& case_dir);

/// The pose truth/meta.json declares ("pose": {"type": ...}), or nullopt. \throws IoError as above.
std::optional<std::string> read_truth_pose(const std::filesystem::path& case_dir);

/// Reads truth/curves.json ({name: {"closed": bool, "points": [[x, y, z], ...]}}), positions
/// multiplied by `to_mm`. \throws IoError naming the file and the curve for malformed content.
std::vector<Curve> read_truth_curves(const std::filesystem::path& path, double to_mm);

/// Reads `case_dir`/truth when it holds surface.ply, landmarks.json and curves.json, else
/// nullopt. Positions are converted with `to_mm` (file units → mm).
/// \throws IoError for a truth directory with missing or malformed files.
std::optional<CaseTruth> read_case_truth(const std::filesystem::path& case_dir, double to_mm);

}  // namespace breastfit::experiments
