#pragma once
/// \file The scan's layer of the report's five overlay figures (front, obliques, sides), which
/// can be drawn before the fit ends. The layer is most of a figure's cost (projecting,
/// binning, rasterising and shading the cropped scan); what depends on the fit (drawings,
/// landmarks, labels, legend) is drawn over it afterwards (render::finish_scene). So that the
/// layer does not depend on the fit, the figures of a fit initialised from landmarks are set up
/// from the template posed by that initialisation (the similarity taking the template's
/// landmarks onto the placed ones, fit/initialization.h):
///  - the body frame: from that posed template's landmarks (mesh::estimate_body_frame);
///  - the crop: the scan without what lies beyond kCropMarginMm (kCropArmMarginMm upwards and
///    sideways, where the arms may be raised) of that posed template's box in the body frame;
///  - the framing: the cropped scan, with the legend's band for the template's drawing names,
///    the off-scan entry and the placed landmarks' entry (the most the figures can show).
/// `breastfit register` draws the layers on a thread of its own while the fit runs
/// (ReportLayerDrawing); every other writer of report.html draws them afterwards. Both give the
/// same bytes. A landmark-free fit has no such pose before its end: its figures are
/// framed from the fitted model (report_figures.h), as before.
#include <array>
#include <atomic>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/landmark_target.h"
#include "breastfit/mesh/body_frame.h"
#include "breastfit/model/rigged_model.h"
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/pipeline/report_figures.h"
#include "breastfit/render/rasterizer.h"
#include "breastfit/render/scene.h"

namespace breastfit::pipeline {

/// One of the overlay figures: its id, title, caption, view and whether it is a small one
/// (ReportFigureOptions::side_size, shown two to a row).
struct OverlayFigureSpec {
  const char* id;
  const char* title;
  const char* caption;
  render::View view;
  bool small;
};
inline constexpr size_t kOverlayFigures = 5;
/// The five overlay figures in report order: front, oblique-right, oblique-left, side-right, side-left.
const std::array<OverlayFigureSpec, kOverlayFigures>& overlay_figure_specs();

/// The render options of overlay figure `k` (size, anti-aliasing, text, view, title) in the
/// body frame `body_to_world`.
render::RenderOptions overlay_render_options(size_t k, const ReportFigureOptions& options,
                                             const Eigen::Matrix4d& body_to_world);

/// Margin of the report's crop of the scan around the body (mm), and upwards and sideways
/// where the arms are when the crop follows the template before the fit.
inline constexpr double kCropMarginMm = 40.0;
inline constexpr double kCropArmMarginMm = 120.0;

/// The scan without the triangles that lie outside `box` (in the body frame of `body_to_world`),
/// with vertex normals: the table, background and far fragments, which would otherwise shrink
/// the torso in the framed image. The whole scan when nothing would be left. (By value: a scan
/// the caller no longer needs is moved in, not copied.)
TriangleMesh crop_scan(TriangleMesh scan, const Eigen::AlignedBox3d& box, const Eigen::Matrix4d& body_to_world);

/// The overlay figures' scan layers, set up by plan_report_layers (drawn by draw_report_layer).
struct ReportLayers {
  mesh::BodyFrame frame;     ///< the figures' body frame (the distance figure's too)
  render::Scene scan_scene;  ///< the cropped scan and the legend's entries (no points): what the layers frame
};

/// Sets up the layers for a fit initialised from `landmarks` (initialization_landmarks) on
/// `scan_mm`; nullopt when there are fewer than 3 (landmark-free) or the scan has no triangles.
std::optional<ReportLayers> plan_report_layers(TriangleMesh scan_mm, const model::RiggedModel& model,
                                               std::vector<fit::LandmarkTarget> landmarks,
                                               const ReportFigureOptions& options);

/// plan_report_layers for a registration's result (its scan and RegisterResult::initial_landmarks).
std::optional<ReportLayers> plan_report_layers(const RegisterResult& result, const model::RiggedModel& model,
                                               const ReportFigureOptions& options);

/// Draws layer `k` (the cropped scan in figure k's view). Deterministic.
render::Rasterizer draw_report_layer(const ReportLayers& layers, size_t k, const ReportFigureOptions& options);

/// The layers of one registration drawn on a thread of their own while the fit runs
/// (start_report_layers): the thread plans them, then draws the five in order. A figure that
/// needs a layer the thread has not begun draws it itself (take), so the report after the fit
/// waits only for a layer already under way. The same pixels whoever draws. (The thread keeps
/// the process's priority: at a lower one, a figure could wait for a layer under way on a thread
/// that the machine's other work starves.)
class ReportLayerDrawing {
 public:
  /// Starts the thread: `plan` (run on it) gives the layers, nullopt for none.
  ReportLayerDrawing(std::function<std::optional<ReportLayers>()> plan, const ReportFigureOptions& options);
  ~ReportLayerDrawing();  ///< stops the thread after the layer under way and waits for it
  ReportLayerDrawing(const ReportLayerDrawing&) = delete;
  ReportLayerDrawing& operator=(const ReportLayerDrawing&) = delete;

  /// The planned layers, nullptr for none; waits for the plan. \throws the plan's error.
  const ReportLayers* layers();
  /// Layer k (once): the thread's (waiting for it when under way), or drawn here when the thread
  /// has not begun it. \pre layers() != nullptr. \throws the drawing's error.
  render::Rasterizer take(size_t k);
  /// Waits until the thread has ended (every layer drawn or taken).
  void wait();
  /// The options the layers are drawn with.
  const ReportFigureOptions& options() const { return options_; }

 private:
  void run(const std::function<std::optional<ReportLayers>()>& plan);

  ReportFigureOptions options_;
  std::optional<ReportLayers> layers_;
  std::promise<void> planned_;
  std::shared_future<void> planned_future_;
  std::array<std::atomic<bool>, kOverlayFigures> claimed_{};
  std::array<std::promise<render::Rasterizer>, kOverlayFigures> drawn_;
  std::array<std::future<render::Rasterizer>, kOverlayFigures> drawn_future_;
  std::thread thread_;
};

/// The template of the registration whose layers are drawn, as the drawing thread gets it: it may
/// wait for the template being loaded elsewhere, and throw that load's error.
using TemplateSource = std::function<std::shared_ptr<const model::RiggedModel>()>;

/// Whether a fit of `landmarks` with `fit_options` may be initialised from landmarks (at least
/// 3 given and used), so that its report's scan layers can be drawn beside it: start_report_layers
/// plans them then (its plan still gives none when fewer than 3 match the template's names).
bool layers_drawn_beside_fit(const std::optional<LandmarkSet>& landmarks, const fit::FitOptions& fit_options);

/// The fit's thread count when the report's layers are drawn beside it: the layer thread keeps a
/// core busy to the end, so an automatic count (`fit_options.threads` 0 and no OMP_NUM_THREADS)
/// leaves it that core (at least one fit thread); any count a person set is kept. One fit thread
/// beside the layers measured 6-12 ms less wall time and 20-28 ms less CPU than two on 2 cores
/// (docs/PERFORMANCE.md, Session 17); the results are the same bits with any count. Without
/// layers beside the fit: `fit_options.threads` as it is.
int fit_threads_beside_layers(const std::optional<LandmarkSet>& landmarks, const fit::FitOptions& fit_options);

/// Starts drawing the layers of a registration on a thread of its own as soon as its scan is
/// prepared (`scan`, as prepare_scan gave it: `register` starts them before the scan's index is
/// built, prepare_target's `before_index`), from the `landmarks` as read and the fit's `fit_options`
/// (use_landmarks, max_landmarks); the thread takes the template from `model` (it may still be
/// loading). The scan is copied here (the caller's may move on); nothing else is kept. Its
/// layers() are nullptr when the fit will be landmark-free. \throws (from layers()) InvalidInput as
/// fit::match_landmarks or prepare_landmarks, and `model`'s error.
std::shared_ptr<ReportLayerDrawing> start_report_layers(const PreparedScan& scan, const std::optional<LandmarkSet>& landmarks,
                                                        const fit::FitOptions& fit_options, TemplateSource model,
                                                        const ReportFigureOptions& options);

/// start_report_layers for `request`'s registration on `target` (after its index is built; the
/// template `request.model`, which must be set).
std::shared_ptr<ReportLayerDrawing> start_report_layers(const RegisterRequest& request, const PreparedTarget& target,
                                                        const ReportFigureOptions& options);

}  // namespace breastfit::pipeline
