#include "breastfit/pipeline/report_layers.h"

#include <algorithm>
#include <cstdlib>
#include <thread>

#include "breastfit/fit/initialization.h"
#include "breastfit/fit/parallel_chunks.h"
#include "breastfit/fit/registration.h"
#include "breastfit/fit/sliding_landmarks.h"
#include "breastfit/mesh/cleanup.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/pipeline/report_figures.h"
#include "breastfit/render/torso_overlays.h"

namespace breastfit::pipeline {

const std::array<OverlayFigureSpec, kOverlayFigures>& overlay_figure_specs() {
  static const std::array<OverlayFigureSpec, kOverlayFigures> kSpecs = {{
      {"front", "Front: scan, landmarks, drawings",
       "The scan seen from the front (the patient's right on the left of the image) with the fitted model's "
       "landmarks (red, labelled), the landmarks placed on the scan (dark, joined to the fitted ones by a line) and "
       "the template's drawings transferred onto the scan: breast contours blue, inframammary folds green, sternum "
       "magenta. Scan parts far outside the torso (table, background) are left out.",
       render::View::Front, false},
      {"oblique-right", "Right oblique",
       "From the patient's front-right, 45 degrees: the lateral side of the right breast and its fold. Parts hidden "
       "behind the body are drawn faded.",
       render::View::Oblique, true},
      {"oblique-left", "Left oblique", "From the patient's front-left, 45 degrees: the left breast and its fold.",
       render::View::ObliqueLeft, true},
      {"side-right", "Right side",
       "The patient's right side (anterior to the right of the image): breast projection, fold and the "
       "mid-axillary line.",
       render::View::Side, true},
      {"side-left", "Left side", "The patient's left side (anterior to the left of the image).",
       render::View::SideLeft, true},
  }};
  return kSpecs;
}

render::RenderOptions overlay_render_options(size_t k, const ReportFigureOptions& o, const Eigen::Matrix4d& body_to_world) {
  const OverlayFigureSpec& spec = overlay_figure_specs()[k];
  ReportFigureOptions sized = o;
  if (spec.small) {  // the four side views are shown two to a row: smaller images
    sized.size = o.side_size;
    sized.text_scale = std::max(1, o.text_scale / 2);
  }
  render::RenderOptions ro = figure_render_options(sized, body_to_world);
  ro.view = spec.view;
  ro.title = spec.title;
  return ro;
}

TriangleMesh crop_scan(TriangleMesh scan, const Eigen::AlignedBox3d& box, const Eigen::Matrix4d& body_to_world) {
  const Eigen::Matrix4d world_to_body = body_to_world.inverse();
  const Eigen::Matrix3d R = world_to_body.topLeftCorner<3, 3>();
  const Vec3 t = world_to_body.topRightCorner<3, 1>();
  std::vector<char> inside(static_cast<size_t>(scan.V.rows()));
  for (Eigen::Index i = 0; i < scan.V.rows(); ++i) inside[i] = box.contains(R * scan.V.row(i).transpose() + t);
  Eigen::Index kept = 0;  // the kept triangles moved to the front, in order
  for (Eigen::Index f = 0; f < scan.F.rows(); ++f)
    if (inside[scan.F(f, 0)] && inside[scan.F(f, 1)] && inside[scan.F(f, 2)]) scan.F.row(kept++) = scan.F.row(f);
  if (kept > 0) {  // what the crop keeps: positions, triangles, and the normals and colours that are whole
    if (!scan.has_normals()) scan.N.resize(0, 3);
    if (!scan.has_colors()) scan.C.resize(0, 3);
    scan.UV.resize(0, 2);
    scan.FUV.resize(0, 3);
    scan.F.conservativeResize(kept, 3);
    mesh::remove_unreferenced_vertices(scan);
  }
  if (scan.num_faces() > 0 && !scan.has_normals()) scan.N = mesh::vertex_normals(scan.V, scan.F);
  return scan;
}

std::optional<ReportLayers> plan_report_layers(TriangleMesh scan_mm, const model::RiggedModel& model,
                                               std::vector<fit::LandmarkTarget> landmarks,
                                               const ReportFigureOptions& options) {
  options.validate();
  if (landmarks.size() < 3 || scan_mm.num_faces() == 0 || model.rest.V.rows() == 0) return std::nullopt;
  // The template as the fit's initialisation places it (the labels corrected as the fit does).
  model::PoseParams params = model::PoseParams::identity(model);
  params.global = fit::initialize_from_landmarks(model, landmarks).similarity;
  TriangleMesh posed;
  posed.V.resize(model.rest.V.rows(), 3);
  for (Eigen::Index i = 0; i < posed.V.rows(); ++i)
    posed.V.row(i) = params.global.apply(model.rest.V.row(i).transpose()).transpose();
  posed.F = model.rest.F;
  mesh::NamedPositions named;
  for (int l = 0; l < static_cast<int>(model.landmarks.size()); ++l)
    named[model.landmarks[l].name] = fit::model_landmark_position(model, l, posed.V, params);

  ReportLayers layers;
  layers.frame = mesh::estimate_body_frame(posed, named);
  const Eigen::Matrix4d world_to_body = layers.frame.body_to_world.inverse();
  const Eigen::Matrix3d R = world_to_body.topLeftCorner<3, 3>();
  const Vec3 t = world_to_body.topRightCorner<3, 1>();
  Eigen::AlignedBox3d box;
  for (Eigen::Index i = 0; i < posed.V.rows(); ++i) box.extend(R * posed.V.row(i).transpose() + t);
  // LPS: the arms, raised by the fit (supine on arm boards), reach sideways (x) and up (+z).
  box.min().array() -= kCropMarginMm;
  box.max().array() += kCropMarginMm;
  box.min().x() -= kCropArmMarginMm - kCropMarginMm;
  box.max().x() += kCropArmMarginMm - kCropMarginMm;
  box.max().z() += kCropArmMarginMm - kCropMarginMm;

  render::SceneMesh scan;
  scan.name = "scan";
  scan.mesh = crop_scan(std::move(scan_mm), box, layers.frame.body_to_world);
  layers.scan_scene.meshes.push_back(std::move(scan));
  for (const model::Drawing& d : model.drawings) {  // the legend's band: no points, only names
    render::ScenePolyline entry;
    entry.name = d.name;
    layers.scan_scene.polylines.push_back(std::move(entry));
  }
  for (const char* name : {kOffScanLegend, render::kPlacedLandmarkLegend}) {  // as overlay_scene adds them
    render::ScenePolyline entry;
    entry.name = name;
    layers.scan_scene.polylines.push_back(std::move(entry));
  }
  return layers;
}

std::optional<ReportLayers> plan_report_layers(const RegisterResult& r, const model::RiggedModel& model,
                                               const ReportFigureOptions& options) {
  return plan_report_layers(r.scan.mesh_mm, model, r.initial_landmarks, options);
}

render::Rasterizer draw_report_layer(const ReportLayers& layers, size_t k, const ReportFigureOptions& options) {
  return render::draw_scene_meshes(layers.scan_scene, overlay_render_options(k, options, layers.frame.body_to_world));
}

ReportLayerDrawing::ReportLayerDrawing(std::function<std::optional<ReportLayers>()> plan,
                                       const ReportFigureOptions& options)
    : options_(options), planned_future_(planned_.get_future().share()) {
  for (size_t k = 0; k < kOverlayFigures; ++k) drawn_future_[k] = drawn_[k].get_future();
  thread_ = std::thread([this, plan = std::move(plan)] { run(plan); });
}

ReportLayerDrawing::~ReportLayerDrawing() {
  for (auto& c : claimed_) c = true;  // no figure will take them: the thread stops after its current layer
  wait();
}

void ReportLayerDrawing::wait() {
  if (thread_.joinable()) thread_.join();
}

void ReportLayerDrawing::run(const std::function<std::optional<ReportLayers>()>& plan) {
  try {
    layers_ = plan();
  } catch (...) {
    planned_.set_exception(std::current_exception());
    return;
  }
  planned_.set_value();
  if (!layers_) return;
  for (size_t k = 0; k < kOverlayFigures; ++k) {
    if (claimed_[k].exchange(true)) continue;  // taken by a figure
    try {
      drawn_[k].set_value(draw_report_layer(*layers_, k, options_));
    } catch (...) {
      drawn_[k].set_exception(std::current_exception());
    }
  }
}

const ReportLayers* ReportLayerDrawing::layers() {
  planned_future_.get();
  return layers_ ? &*layers_ : nullptr;
}

render::Rasterizer ReportLayerDrawing::take(size_t k) {
  if (!claimed_.at(k).exchange(true)) return draw_report_layer(*layers(), k, options_);
  return drawn_future_[k].get();
}

bool layers_drawn_beside_fit(const std::optional<LandmarkSet>& landmarks, const fit::FitOptions& fit_options) {
  return landmarks && fit_options.use_landmarks && landmarks->points.size() >= 3 &&
         (fit_options.max_landmarks < 0 || fit_options.max_landmarks >= 3);
}

int fit_threads_beside_layers(const std::optional<LandmarkSet>& landmarks, const fit::FitOptions& fit_options) {
  if (!layers_drawn_beside_fit(landmarks, fit_options) || fit_options.threads != 0 || std::getenv("OMP_NUM_THREADS"))
    return fit_options.threads;
  return std::max(1, fit::resolve_threads(0) - 1);
}

std::shared_ptr<ReportLayerDrawing> start_report_layers(const PreparedScan& scan, const std::optional<LandmarkSet>& landmarks,
                                                        const fit::FitOptions& fit_options, TemplateSource model,
                                                        const ReportFigureOptions& options) {
  if (!layers_drawn_beside_fit(landmarks, fit_options))  // a landmark-free fit: no copy of the scan
    return std::make_shared<ReportLayerDrawing>([] { return std::optional<ReportLayers>(); }, options);
  return std::make_shared<ReportLayerDrawing>(
      [scan_mm = scan.mesh_mm, units = scan.units, landmarks, fit_options, model = std::move(model),
       options]() mutable -> std::optional<ReportLayers> {
        const std::shared_ptr<const model::RiggedModel> m = model();
        std::vector<std::pair<std::string, Vec3>> landmarks_mm;
        if (landmarks) landmarks_mm = prepare_landmarks(*landmarks, units);
        return plan_report_layers(std::move(scan_mm), *m,
                                  initialization_landmarks(fit::match_landmarks(*m, landmarks_mm), fit_options), options);
      },
      options);
}

std::shared_ptr<ReportLayerDrawing> start_report_layers(const RegisterRequest& req, const PreparedTarget& target,
                                                        const ReportFigureOptions& options) {
  return start_report_layers(target.scan, req.landmarks, req.options, [model = req.model] { return model; }, options);
}

}  // namespace breastfit::pipeline
