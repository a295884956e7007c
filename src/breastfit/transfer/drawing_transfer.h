#pragma once
/// \file Transfer of the template's surgical drawings from the fitted model onto the scan
/// (docs/TRANSFER.md): each drawing is evaluated on the fitted (posed)
/// template, resampled every ~1 mm on the fitted surface, projected onto the scan where the scan
/// supports it (the model's point is kept and flagged elsewhere), and smoothed lightly while
/// staying on the surface.
///
/// Example:
/// \code
///   fit::ScanTarget scan(scan_mm);
///   auto curves = transfer::transfer_drawings(model, fit.vertices, scan);
///   io::write_markups(dir / "drawings.mrk.json", transfer::to_markups(curves), {.units = "mm"});
/// \endcode
#include <memory>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/model/rigged_model.h"
#include "breastfit/spatial/closest_point_index.h"

namespace breastfit::transfer {

/// How a model point finds its scan point.
enum class ProjectionMode {
  ClosestPoint,  ///< the exact closest point of the scan within max_distance_mm (default: see docs/TRANSFER.md)
  AlongNormal,   ///< the nearest intersection of the model's normal line with the scan within max_distance_mm
};

struct TransferOptions {
  ProjectionMode mode = ProjectionMode::ClosestPoint;  ///< see ProjectionMode
  double max_distance_mm = 10.0;     ///< farther scan points do not support the curve, mm (> 0)
  bool reject_scan_border = true;    ///< a scan point on the scan's open border (hole rim, edge of the scanned area) does not support the curve; set false for point-cloud splats
  double max_normal_angle_deg = 60;  ///< scan vs model normal angle (unsigned) beyond which a match is rejected, degrees in (0, 90]
  double spacing_mm = 1.0;           ///< resampling step along the curve, mm (> 0)
  int smoothing_passes = 3;          ///< Laplacian passes, each followed by re-projection onto the surface (>= 0)
  double smoothing_weight = 0.5;     ///< weight of each Laplacian pass, in [0, 1]
  /// Hanging breasts: a model point on skin facing caudally (−n·superior above this) lies on the
  /// underside of an overhang, while the fold — where a surgeon draws the IMF — is behind it, at
  /// the chest wall. Such a point slides posteriorly along the fitted surface until the skin stops
  /// facing down (docs/TRANSFER.md "Hanging breasts"). Needs the body's axes (set_body_axes;
  /// transfer_drawings takes them from the fitted landmarks). In (0, 1]; 1 = never.
  double fold_facing_down_cos = 0.5;
  double fold_max_slide_mm = 60.0;   ///< longest slide, mm (>= 0)

  /// \throws InvalidInput naming the field, its value and the rule it violates
  void validate() const;
};

/// One drawing on the scan.
struct TransferredCurve {
  std::string name;
  bool closed = false;
  Points points;                 ///< #P by 3, mm, scan frame, ~spacing_mm apart (closed: first not repeated)
  std::vector<bool> supported;   ///< #P flags: true = on the scan, false = the fitted model's point (hole, border, nothing near)
  double length_mm = 0;          ///< polyline length (closing segment included)
  double supported_fraction = 0; ///< fraction of points supported by the scan, in [0, 1] — higher is better
  double mean_model_to_scan_mm = 0;  ///< mean |model point − scan point| over the supported points
                                     ///< (before smoothing); 0 when none is supported — lower is better
};

/// Transfers polylines lying on a fitted surface onto one scan. Built once per scan and fit.
class DrawingTransfer {
 public:
  /// \param scan    the scan (mm); kept by reference, must outlive this object
  /// \param fitted  the fitted template surface (mm, same frame); copied into an index
  /// \throws InvalidInput for invalid options or a fitted mesh without triangles
  DrawingTransfer(const fit::ScanTarget& scan, const TriangleMesh& fitted_mm, const TransferOptions& options = {});
  ~DrawingTransfer();

  /// Transfers one polyline (#P by 3, mm, on or near the fitted surface; >= 1 point).
  /// \throws InvalidInput for an empty or non-finite polyline
  TransferredCurve transfer(const std::string& name, bool closed, const Points& model_points_mm) const;

  /// One point on or near the fitted surface, projected onto the scan (no resampling/smoothing).
  struct PointProjection {
    Vec3 model_point = Vec3::Zero();  ///< closest point of the fitted surface, mm
    Vec3 point = Vec3::Zero();        ///< the scan point when supported, else model_point, mm
    bool supported = false;           ///< a scan point passed the distance / border / normal tests
    double model_to_scan_mm = 0;      ///< |point − model_point| (0 when unsupported)
  };
  PointProjection project_point(const Vec3& q) const;

  /// The body's superior and anterior directions (unit, orthogonal) in the scan frame: enables
  /// the fold slide of TransferOptions::fold_facing_down_cos in transfer().
  void set_body_axes(const Vec3& superior, const Vec3& anterior);

  /// A point of the fitted surface moved out of an overhang (see fold_facing_down_cos); the
  /// point's closest surface point when it is not under one or no body axes are set.
  Vec3 slide_into_fold(const Vec3& q) const;

  const TransferOptions& options() const { return options_; }

 private:
  struct Projection;
  // `scan_face` (in/out, optional): ScanTarget::match's warm start (ClosestPoint mode only).
  Projection project(const Vec3& model_point, const Vec3& model_normal, Index* scan_face = nullptr) const;
  // slide_into_fold's closest point, its first query warm-started from `hint_face` (< 0: none).
  spatial::ClosestPoint slide(const Vec3& q, Index hint_face) const;

  const fit::ScanTarget& scan_;
  spatial::ClosestPointIndex fitted_;
  TransferOptions options_;
  std::optional<std::pair<Vec3, Vec3>> body_axes_;  // superior, anterior
  struct Rays;
  std::unique_ptr<Rays> rays_;  // only for ProjectionMode::AlongNormal
};

/// Every drawing of `model` evaluated on the posed vertices and transferred onto `scan`.
/// \param[in] posed_mm  #V by 3 posed template vertices (mm, scan frame), e.g. FitResult::vertices
/// \throws InvalidInput when posed_mm does not match the model or for invalid options
std::vector<TransferredCurve> transfer_drawings(const model::RiggedModel& model, const Points& posed_mm,
                                                const fit::ScanTarget& scan, const TransferOptions& options = {});

/// The curves as markups (positions unchanged, mm; closed curves → Slicer "ClosedCurve").
Markups to_markups(const std::vector<TransferredCurve>& curves);

}  // namespace breastfit::transfer
