#pragma once
/// \file Breast measurements on the fitted template, beyond the paper: per-breast volume,
/// sternal-notch-to-nipple and nipple-to-inframammary-fold distances, inter-nipple distance and
/// left/right symmetry ratios (docs/TRANSFER.md "Breast measurements").
///
/// Volume (measure_breasts): the skin inside the breast contour `breast_contour_R/L` of the
/// fitted model against a chest wall spanning the contour (curve_region.h: curve_volume), the
/// same rule as `breastfit volume` on any surface and curve. Underneath, region_volume:
/// the solid between the skin of a vertex region and a chest-wall surface under it, a fill of the region with
/// every vertex outside it held at its skin position (ChestWallFill):
///  - Membrane (default): harmonic fill, Σ‖∇x‖² minimal (uniform graph Laplacian L x = 0 on the
///    region): depends only on the region's border, like the "surface spanning the breast
///    footprint" of clinical 3D volumetry; robust to where exactly the border is drawn, slightly
///    below a convex chest wall (overestimates by the chest's sagitta over the footprint).
///  - ThinPlate: bi-Laplacian fill, Σ‖L x‖² minimal: continues the surrounding skin with its slope
///    and curvature (two rings of skin enter). Exact on a curved chest when the region's border is
///    where the breast starts, but when the border lies on the breast's rising flank it
///    continues that slope and cuts the breast (bench: see docs/TRANSFER.md).
/// Both reproduce planes, so a bump on a flat chest gets exactly the bump's volume. With a
/// margin the region is first grown by every vertex within margin_mm (along mesh edges) of it,
/// so the fill is anchored on skin that is surely chest wall, beyond the breast's base; the
/// added band contributes (almost) nothing since the fill follows the skin there. The closed
/// solid is skin ∪ reversed fill (they share the region's border); its volume follows from the
/// divergence theorem.
#include <optional>
#include <string>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::transfer {

class VolumeCache;

/// How the chest wall under a region is filled (see the file comment).
enum class ChestWallFill { Membrane, ThinPlate };

struct VolumeOptions {
  ChestWallFill fill = ChestWallFill::Membrane;  ///< see the file comment and docs/TRANSFER.md
  double margin_mm = 0.0;   ///< grow the region by this (edge-path distance) before filling, mm (>= 0)
  /// \throws InvalidInput for a negative or non-finite margin
  void validate() const;
};

/// The solid under a region of a surface.
struct RegionVolume {
  double volume_mm3 = 0;  ///< skin minus chest-wall fill (negative when the skin lies under the fill)
  Points chest_wall;      ///< #V by 3: the mesh with the region's vertices moved onto the fill
};

/// Volume between the skin of `region` (vertex indices of `surface`) and its thin-plate fill.
/// \param surface  triangle mesh, outward counter-clockwise triangles, mm
/// \param region   vertex indices (unique, in range, at least one); must not touch every vertex
/// \param cache    optional (volume_cache.h): the surface's topology and the fill's factorisation
///                 reused when they are those of an earlier call (the same result)
/// \throws InvalidInput for an empty region, an index out of range, a region without outside
///         vertices, or a singular fill (a region not attached to the rest of the mesh)
RegionVolume region_volume(const TriangleMesh& surface, const std::vector<Index>& region,
                           const VolumeOptions& options = {}, VolumeCache* cache = nullptr);

/// One breast's numbers; nullopt when an input (landmark, curve, region) is missing.
struct BreastSide {
  std::optional<double> volume_ml;           ///< cm³ (1 ml = 1000 mm³)
  std::optional<double> notch_to_nipple_mm;  ///< straight distance sternal_notch → nipple
  std::optional<double> nipple_to_imf_mm;    ///< straight distance nipple → lowest point of the fold
  std::optional<Vec3> imf_lowest_mm;         ///< that lowest point (on imf_X, else breast_contour_X)
};

struct BreastMeasurements {
  BreastSide right, left;
  std::optional<double> inter_nipple_mm;      ///< nipple_R ↔ nipple_L
  std::optional<double> volume_ratio;         ///< left / right volume (1 = symmetric)
  std::optional<double> notch_to_nipple_ratio;  ///< left / right
  std::optional<double> nipple_to_imf_ratio;    ///< left / right
  VolumeOptions volume_options;               ///< the chest wall used for the volumes
  std::vector<std::string> warnings;          ///< missing inputs, negative volumes
};

/// One side's part of measure_breasts: its numbers and warnings.
struct BreastSideMeasurement {
  BreastSide numbers;
  std::vector<std::string> warnings;
};

/// measure_breasts' work for one breast, `side` 'R' or 'L' (the same numbers): the two sides are
/// independent, so a caller may run them as two of its own tasks and join them with
/// join_breast_sides (pipeline::register_prepared's re-fit balances them against its other tasks).
/// \throws InvalidInput when posed_mm does not match the model or side is neither 'R' nor 'L'
BreastSideMeasurement measure_breast_side(const model::RiggedModel& model, const Points& posed_mm, char side,
                                          const VolumeOptions& options = {}, VolumeCache* cache = nullptr);

/// The measurements from the two sides of measure_breast_side (what measure_breasts returns).
BreastMeasurements join_breast_sides(const model::RiggedModel& model, const Points& posed_mm,
                                     BreastSideMeasurement right, BreastSideMeasurement left,
                                     const VolumeOptions& options = {});

/// Measures both breasts on the posed template.
/// Vertical ("lowest") is the direction xiphoid → sternal_notch of the posed model (falls back
/// to the +z axis of posed_mm, with a warning, when a landmark is missing).
/// \param posed_mm  #V by 3 posed vertices (mm), e.g. FitResult::vertices
/// \param cache     optional (volume_cache.h): kept across the measurements of one template (a
///                  session's re-fits) it spares the topology and the fills' factorisations
///                  (the same result)
/// \param threads   up to 2: the two breasts measured at the same time (the same result)
/// \throws InvalidInput when posed_mm does not match the model
BreastMeasurements measure_breasts(const model::RiggedModel& model, const Points& posed_mm,
                                   const VolumeOptions& options = {}, VolumeCache* cache = nullptr,
                                   unsigned threads = 1);

}  // namespace breastfit::transfer
