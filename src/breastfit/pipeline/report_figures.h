#pragma once
/// \file The images of the registration report (report.html), rendered headlessly with the
/// render layer in the scan's body frame:
///  1. front view of the scan with the fitted model's landmarks (labelled red discs) and the
///     transferred drawings (one colour each, legend; pale thin segments where the scan has
///     nothing under the drawing and it follows the fitted model instead);
///  2. the same from the front-right (oblique) — the breast's lateral side and the fold;
///  3. front view of the fitted model coloured by its distance to the scan (viridis over a fixed
///     0 … `distance_range_mm` range so reports are comparable; grey where the scan has no
///     surface to compare with: over holes and beyond the scanned area).
/// The body frame comes from the fitted model's landmarks (mesh::body_frame_from_landmarks),
/// else from the fitted model's shape. Deterministic: the same result gives identical pixels.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "breastfit/pipeline/register_scan.h"
#include "breastfit/render/image.h"
#include "breastfit/render/scene.h"

namespace breastfit::pipeline {

struct ReportFigureOptions {
  int size = 900;                   ///< square images, pixels (>= 64)
  int supersample = 2;              ///< anti-aliasing factor, 1..4
  int text_scale = 2;               ///< font scale of labels, legend and colour bar (>= 1)
  double distance_range_mm = 10.0;  ///< colour-map range of the distance figure: 0 … this (> 0)
  bool parallel = true;             ///< render the figures concurrently (same pixels either way)

  /// \throws InvalidInput naming the field, its value and the rule it violates
  void validate() const;
};

/// One rendered image of the report.
struct ReportFigure {
  std::string id;       ///< "front", "oblique", "distance" (also the file stem of exported images)
  std::string title;    ///< drawn in the image's top-left corner
  std::string caption;  ///< one or two sentences for the reader, plain text
  render::Image image;
  std::vector<std::uint8_t> png;  ///< image.encode_png()
};

struct ReportFigures {
  std::vector<ReportFigure> figures;   ///< front, oblique, distance (in this order)
  std::string body_frame;              ///< how the views were oriented, e.g. "landmarks: ..."
  Eigen::VectorXd distances_mm;        ///< model_to_scan_distances (shown in the distance figure)
};

/// Colour of a transferred drawing in the figures (and of its swatch in the report), by kind as
/// in scan_painted.ply: breast contours blue, inframammary folds green, sternum magenta (not red:
/// red is for landmarks); any other drawing purple, teal or dark grey by its index — colours that
/// stand out on skin.
render::Rgb report_curve_colour(const std::string& name, size_t index);

/// Distance (mm) from every fitted vertex to the closest point of the scan; NaN (drawn grey)
/// where the scan does not cover the vertex (RegisterResult::coverage, metrics/surface_coverage.h:
/// over a hole, beyond the scanned area, far from the scan; without a coverage, NaN where the
/// closest point lies on the scan's open border, never for a point cloud). The finite values
/// are the ones behind RegisterResult::surface.
Eigen::VectorXd model_to_scan_distances(const RegisterResult& result);

/// The overlay scene of figures 1 and 2: the scan (without what lies more than 40 mm outside the
/// fitted model's box in the body frame: table, background, far fragments), the fitted
/// landmarks and the drawings.
render::Scene overlay_scene(const RegisterResult& result, const ReportFigureOptions& options = {});

/// Renders the three figures. \throws InvalidInput for invalid options or an empty result.
ReportFigures render_report_figures(const RegisterResult& result, const ReportFigureOptions& options = {});

}  // namespace breastfit::pipeline
