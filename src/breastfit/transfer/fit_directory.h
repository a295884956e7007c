#pragma once
/// \file Reading back the output directory of `breastfit register` (fitted.ply, params.json,
/// report.json): the fitted template surface in mm in the scan's frame, and the scan's units.
#include <filesystem>
#include <string>

#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::transfer {

struct FitDirectory {
  std::filesystem::path dir;
  std::string units = "mm";   ///< units of the scan and of every file of the fit ("mm" or "m")
  double to_mm = 1.0;         ///< file units → mm
  TriangleMesh fitted_mm;     ///< the fitted template (template triangles), mm, scan frame
  bool from_params = false;   ///< true: posed from params.json (double precision); false: fitted.ply
};

/// Reads a register output directory. report.json must be there: it is written last, so a
/// directory without it holds an incomplete set (io/output_set.h); a report with status
/// "not_usable" has no fit beside it. Units come from report.json ("units"; "mm" when absent).
/// With a model, the surface is the model posed by params.json (exact), plus its
/// "surface_detail" offsets along the posed normals when present (fit/surface_detail.h), and
/// fitted.ply, when present, must agree with it (same vertex count, within 0.5 mm + float
/// rounding) — this catches a fit made with another template. Without a model, or without
/// params.json, it is fitted.ply converted to mm.
/// \throws IoError for a missing directory, no report.json, a not-usable report,
///         missing/unreadable files, or a fitted.ply that does not match the template; InvalidInput for invalid parameters (see params_json.h)
FitDirectory read_fit_directory(const std::filesystem::path& dir, const model::RiggedModel* model = nullptr);

}  // namespace breastfit::transfer
