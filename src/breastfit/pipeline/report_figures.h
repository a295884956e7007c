#pragma once
/// \file The images of the registration report (report.html), rendered headlessly with the
/// render layer in the scan's body frame:
///  1. front view of the scan with the fitted model's landmarks (labelled red discs), the
///     landmarks placed on the scan (dark discs, a line to the fitted one) and the transferred
///     drawings (the drawing palette, legend; pale thin segments where the scan has nothing under
///     the drawing and it follows the fitted model instead);
///  2.–5. the same from the front-right and front-left (obliques, 45°) and from the right and
///     left sides (laterals), smaller (shown two to a row);
///  6. front view of the fitted model coloured by its distance to the scan (viridis from 0 to
///     the 95th percentile rounded up to a nice number, or a fixed range; grey where the scan has
///     no surface to compare with: over holes and beyond the scanned area).
/// With a template (a fit initialised from landmarks, report_layers.h) the views are set up from
/// the template as that initialisation placed it: the body frame from its landmarks, the scan
/// cropped around it; without one (a landmark-free fit), the body frame comes from the fitted
/// model's landmarks (mesh::body_frame_from_landmarks), else from the fitted model's shape, and
/// the crop from the fitted model. Deterministic: the same result gives identical pixels.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "breastfit/model/rigged_model.h"
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/render/image.h"
#include "breastfit/render/scene.h"

namespace breastfit::pipeline {

struct ReportLayers;
class ReportLayerDrawing;

struct ReportFigureOptions {
  int size = 900;                   ///< front and distance figures: square images, pixels (>= 64)
  int side_size = 450;              ///< oblique and side figures (shown two to a row), pixels (>= 64)
  int supersample = 2;              ///< anti-aliasing factor, 1..4
  int text_scale = 2;               ///< font scale of labels, legend and colour bar (>= 1); half on side figures
  /// Colour-map range of the distance figure, 0 … this (> 0); nullopt: distance_scale_mm.
  std::optional<double> distance_range_mm;
  bool parallel = true;             ///< render the figures concurrently, one worker per core (same pixels either way)

  /// \throws InvalidInput naming the field, its value and the rule it violates
  void validate() const;
};

/// One rendered image of the report.
struct ReportFigure {
  std::string id;       ///< "front", "oblique-right", "oblique-left", "side-right", "side-left", "distance"
  std::string title;    ///< drawn in the image's top-left corner
  std::string caption;  ///< one or two sentences for the reader, plain text
  render::Image image;
  std::vector<std::uint8_t> png;  ///< image.encode_png()
};

struct ReportFigures {
  std::vector<ReportFigure> figures;   ///< in the order of ReportFigure::id
  std::string body_frame;              ///< how the views were oriented, e.g. "landmarks: ..."
  Eigen::Matrix4d body_to_world = Eigen::Matrix4d::Identity();  ///< that body frame
  Eigen::VectorXd distances_mm;        ///< model_to_scan_distances (shown in the distance figure)
  double distance_scale_mm = 0;        ///< the distance figure's colour-bar top (mm)
};

/// Colour of a transferred drawing in the figures (and of its swatch in the report and the
/// workstation): the one drawing palette, mesh::drawing_colour — the same as `render` and
/// scan_painted.ply (breast contours blue, inframammary folds green, sternum magenta; others
/// purple, teal or dark grey by index; red is for landmarks).
render::Rgb report_curve_colour(const std::string& name, size_t index);

/// Distance (mm) from every fitted vertex to the closest point of the scan; NaN (drawn grey)
/// where the scan does not cover the vertex (RegisterResult::coverage, metrics/surface_coverage.h:
/// over a hole, beyond the scanned area, far from the scan; without a coverage, NaN where the
/// closest point lies on the scan's open border, never for a point cloud). The finite values
/// are the ones behind RegisterResult::surface.
Eigen::VectorXd model_to_scan_distances(const RegisterResult& result);

/// The top of the distance figure's colour scale: the 95th percentile of the finite distances
/// rounded up to 1, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 × 10^k mm, at least kMinDistanceScaleMm (also
/// when there are none). A close fit gets a fine scale, a loose one a coarse scale, so the map is
/// never almost all one colour.
inline constexpr double kMinDistanceScaleMm = 1.0;
double distance_scale_mm(const Eigen::VectorXd& distances_mm);

/// How the distance figure colours the fitted model (the one place that decides it): viridis
/// from 0 to `hi_mm`, NaN (no scan to compare with) grey, labelled "distance" in mm.
render::ScalarField distance_field(const Eigen::VectorXd& distances_mm, double hi_mm);

/// The legend entry of the drawings' pale parts (off the scan).
inline constexpr const char* kOffScanLegend = "pale: no scan under it";

/// The render options every figure starts from: square `options.size` images, anti-aliasing,
/// text scale and margin, in the body frame `body_to_world`.
render::RenderOptions figure_render_options(const ReportFigureOptions& options, const Eigen::Matrix4d& body_to_world);

/// The overlay scene of the front, oblique and side figures: the scan (without what lies more than 40 mm outside the
/// fitted model's box in the body frame: table, background, far fragments), the fitted
/// landmarks, the placed landmarks joined to them, and the drawings.
render::Scene overlay_scene(const RegisterResult& result, const ReportFigureOptions& options = {});

/// Renders the six figures, framed from the fitted model (the landmark-free way, for a result
/// without its template). \throws InvalidInput for invalid options or an empty result.
ReportFigures render_report_figures(const RegisterResult& result, const ReportFigureOptions& options = {});

/// Renders the six figures over `layers` (plan_report_layers with the same options): their body
/// frame and scan layers, with the overlays, the distance figure and the PNGs.
/// \throws InvalidInput for invalid options or an empty result.
ReportFigures render_report_figures(const RegisterResult& result, const ReportLayers& layers,
                                    const ReportFigureOptions& options = {});

/// The figures as report.html shows them: over the scan layers of `drawing` (started beside the
/// fit with the same options; it may have none: landmark-free) or, without one, over
/// plan_report_layers(result, model) when the fit was initialised from landmarks; otherwise
/// framed from the fitted model. The same bytes either way.
/// \throws as render_report_figures; InvalidInput when `drawing` used other figure sizes.
ReportFigures report_figures(const RegisterResult& result, const model::RiggedModel& model,
                             const ReportFigureOptions& options = {},
                             const std::shared_ptr<ReportLayerDrawing>& drawing = nullptr);

}  // namespace breastfit::pipeline
