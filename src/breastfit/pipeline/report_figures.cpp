#include "breastfit/pipeline/report_figures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <thread>
#include <utility>

#include "breastfit/core/errors.h"
#include "breastfit/core/task_queue.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/mesh/body_frame.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/pipeline/report_layers.h"
#include "breastfit/render/torso_overlays.h"

namespace breastfit::pipeline {
namespace {

/// A stretch of a transferred drawing whose points are all on the scan, or all off it.
struct Run {
  bool supported = true;
  bool closed = false;  ///< the whole curve, closed, in one status
  std::vector<Eigen::Index> points;
};

/// Splits a curve into runs by segment status (a segment is on the scan when both its ends are).
std::vector<Run> runs_of(const transfer::TransferredCurve& c) {
  const Eigen::Index n = c.points.rows();
  if (n == 0) return {};
  auto on = [&](Eigen::Index i) { return static_cast<size_t>(i) >= c.supported.size() || c.supported[i]; };
  if (n == 1) return {{on(0), false, {0}}};
  const bool wraps = c.closed && n > 2;
  const Eigen::Index nseg = wraps ? n : n - 1;
  auto seg_on = [&](Eigen::Index s) { return on(s) && on((s + 1) % n); };
  bool uniform = true;
  for (Eigen::Index s = 1; s < nseg && uniform; ++s) uniform = seg_on(s) == seg_on(0);
  if (uniform) {
    Run r{seg_on(0), wraps, {}};
    for (Eigen::Index i = 0; i < n; ++i) r.points.push_back(i);
    return {r};
  }
  // Start a closed curve at a change of status so that no run is cut at the array's end.
  Eigen::Index start = 0;
  if (wraps)
    while (seg_on(start) == seg_on((start + nseg - 1) % nseg)) ++start;
  std::vector<Run> runs;
  for (Eigen::Index k = 0; k < nseg; ++k) {
    const Eigen::Index s = (start + k) % n;
    if (runs.empty() || runs.back().supported != seg_on(s)) runs.push_back({seg_on(s), false, {s}});
    runs.back().points.push_back((s + 1) % n);
  }
  return runs;
}

Points rows_of(const Points& P, const std::vector<Eigen::Index>& idx) {
  Points out(static_cast<Eigen::Index>(idx.size()), 3);
  for (size_t i = 0; i < idx.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = P.row(idx[i]);
  return out;
}

/// Pale version of a drawing colour (the parts that follow the fitted model, not the scan).
render::Rgb pale(render::Rgb c) { return render::mix(c, {255, 255, 255}, 0.5); }

/// "2.5", "10": a scale value without trailing zeros.
std::string format_mm(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

mesh::BodyFrame body_frame_of(const RegisterResult& r) {
  mesh::NamedPositions named;
  for (const auto& p : r.model_landmarks_mm.points) named[p.name] = p.position;
  return mesh::estimate_body_frame(r.fitted_mm, named);
}

/// The scan as the overlay figures of a landmark-free fit show it: without what lies more than
/// kCropMarginMm outside the fitted model's box in the body frame, with vertex normals.
TriangleMesh overlay_scan(const RegisterResult& r, const Eigen::Matrix4d& body_to_world) {
  if (r.scan.mesh_mm.num_faces() == 0 || r.fitted_mm.V.rows() == 0) {
    TriangleMesh scan = r.scan.mesh_mm;
    if (scan.num_faces() > 0 && !scan.has_normals()) scan.N = mesh::vertex_normals(scan.V, scan.F);
    return scan;
  }
  const Eigen::Matrix4d world_to_body = body_to_world.inverse();
  const Eigen::Matrix3d R = world_to_body.topLeftCorner<3, 3>();
  const Vec3 t = world_to_body.topRightCorner<3, 1>();
  Eigen::AlignedBox3d box;
  for (Eigen::Index i = 0; i < r.fitted_mm.V.rows(); ++i) box.extend(R * r.fitted_mm.V.row(i).transpose() + t);
  box.min().array() -= kCropMarginMm;
  box.max().array() += kCropMarginMm;
  return crop_scan(r.scan.mesh_mm, box, body_to_world);
}

/// The overlays of the front, oblique and side figures (drawings, landmarks), without the scan.
render::Scene overlay_marks(const RegisterResult& r, const ReportFigureOptions& o) {
  render::OverlaySizes sizes(o.size);
  sizes.line_width_px *= 1.3;  // drawings are the point of the figure: a little bolder than `render`
  render::Scene scene;
  bool any_off_scan = false;
  for (size_t k = 0; k < r.drawings_on_scan.size(); ++k) {
    const auto& c = r.drawings_on_scan[k];
    const render::Rgb colour = report_curve_colour(c.name, k);
    std::vector<Run> runs = runs_of(c);
    // The legend shows the first polyline of each name: put a run on the scan first.
    std::stable_partition(runs.begin(), runs.end(), [](const Run& run) { return run.supported; });
    bool named = false;
    for (const Run& run : runs) {
      render::ScenePolyline l;
      l.name = named ? "" : c.name;
      named = true;
      l.points = rows_of(c.points, run.points);
      l.closed = run.closed;
      l.colour = run.supported ? colour : pale(colour);
      l.width_px = run.supported ? sizes.line_width_px : std::max(1.5, 0.6 * sizes.line_width_px);
      any_off_scan = any_off_scan || !run.supported;
      scene.polylines.push_back(std::move(l));
    }
  }
  if (any_off_scan) {
    render::ScenePolyline legend_only;  // no points: only a legend entry
    legend_only.name = kOffScanLegend;
    legend_only.colour = pale({90, 90, 90});
    legend_only.width_px = std::max(1.5, 0.6 * sizes.line_width_px);
    scene.polylines.push_back(std::move(legend_only));
  }
  std::vector<NamedPoint> placed;
  for (const fit::LandmarkTarget& t : r.fit.landmarks) placed.push_back({t.name, t.position});
  render::add_placed_landmarks(scene, placed, r.model_landmarks_mm.points, sizes);
  for (const auto& p : r.model_landmarks_mm.points) scene.points.push_back(render::landmark_point(p.name, p.position, sizes));
  return scene;
}

render::Scene overlay_scene_with(const RegisterResult& r, const ReportFigureOptions& o, TriangleMesh scan) {
  render::Scene scene = overlay_marks(r, o);
  scene.meshes.emplace_back();
  scene.meshes.back().name = "scan";
  scene.meshes.back().mesh = std::move(scan);
  return scene;
}

/// The six figures in the body frame `frame`; overlay figure k's meshes pass by `layer(k, scene)`
/// (`scene`: its overlays), the distance figure's here.
ReportFigures render_figures(const RegisterResult& r, const ReportFigureOptions& o, const mesh::BodyFrame& frame,
                             const render::Scene& scene, const render::Scene& side_scene,
                             const std::function<render::Rasterizer(size_t, const render::Scene&)>& layer,
                             bool distance_first = false) {
  ReportFigures out;
  out.body_frame = frame.description;
  out.body_to_world = frame.body_to_world;
  const auto& specs = overlay_figure_specs();
  out.figures.resize(specs.size() + 1);
  for (size_t k = 0; k < specs.size(); ++k) out.figures[k] = {specs[k].id, specs[k].title, specs[k].caption, {}, {}};
  ReportFigure& dist_fig = out.figures.back();
  dist_fig = {"distance", "Fitted model: distance to the scan", "", {}, {}};

  auto overlay_figure = [&](size_t k) {
    ReportFigure& f = out.figures[k];
    const render::Scene& marks = specs[k].small ? side_scene : scene;
    f.image = render::finish_scene(layer(k, marks), marks, overlay_render_options(k, o, frame.body_to_world));
    f.png = f.image.encode_png();
  };
  auto distance_figure = [&] {
    out.distances_mm = model_to_scan_distances(r);
    const double hi = o.distance_range_mm ? *o.distance_range_mm : distance_scale_mm(out.distances_mm);
    out.distance_scale_mm = hi;
    dist_fig.caption = "The fitted model coloured by its distance to the scan, 0 to " + format_mm(hi) +
                       " mm (dark: close, yellow: far; farther than " + format_mm(hi) + " mm is yellow too" +
                       (o.distance_range_mm ? "" : "; the scale's top is the 95th percentile of the distances, rounded up") +
                       "). Grey: no scan to compare with (holes, beyond the scanned area).";
    render::Scene dist;
    dist.meshes.emplace_back();
    dist.meshes.back().name = "fitted";
    dist.meshes.back().mesh = r.fitted_mm;
    dist.meshes.back().scalars = distance_field(out.distances_mm, hi);
    render::RenderOptions ro = figure_render_options(o, frame.body_to_world);
    ro.view = render::View::Front;
    ro.title = dist_fig.title;
    dist_fig.image = render::render_scene(dist, ro);
    dist_fig.png = dist_fig.image.encode_png();
  };
  // Each figure is rendered by one task from shared read-only inputs into its own slot, so the
  // pixels do not depend on `parallel`. The tasks are taken in order by one worker per core
  // (more would not finish sooner, only hold more full-size image buffers at once); the two
  // large figures come first and last, so they are rarely in memory together.
  // With `distance_first` (the layers drawn on a thread of their own, which may still be drawing
  // the last ones) the distance figure, which needs no layer, comes first, so that a worker does
  // not wait for a layer under way while it could be drawing it.
  const size_t n = specs.size() + 1;
  run_in_order(n, o.parallel ? std::thread::hardware_concurrency() : 1, [&](size_t k) {
    const size_t figure = distance_first ? (k + n - 1) % n : k;
    if (figure < specs.size())
      overlay_figure(figure);
    else
      distance_figure();
  });
  return out;
}

void check_result(const RegisterResult& r, const ReportFigureOptions& o) {
  o.validate();
  if (r.fitted_mm.V.rows() == 0 || r.scan.mesh_mm.V.rows() == 0)
    throw InvalidInput("render_report_figures: the result has no fitted model or no scan");
}

/// The figures over scan layers: overlay figure k's layer from `layer(k)`.
ReportFigures render_over_layers(const RegisterResult& r, const mesh::BodyFrame& frame, const ReportFigureOptions& o,
                                 const std::function<render::Rasterizer(size_t)>& layer, bool distance_first = false) {
  check_result(r, o);
  const render::Scene scene = overlay_marks(r, o);
  ReportFigureOptions side = o;
  side.size = o.side_size;
  const render::Scene side_scene = overlay_marks(r, side);
  return render_figures(r, o, frame, scene, side_scene, [&](size_t k, const render::Scene&) { return layer(k); },
                        distance_first);
}

}  // namespace

void ReportFigureOptions::validate() const {
  if (size < 64 || size > 8192)
    throw InvalidInput("ReportFigureOptions: size must be in [64, 8192], got " + std::to_string(size));
  if (supersample < 1 || supersample > 4)
    throw InvalidInput("ReportFigureOptions: supersample must be in [1, 4], got " + std::to_string(supersample));
  if (text_scale < 1 || text_scale > 16)
    throw InvalidInput("ReportFigureOptions: text_scale must be in [1, 16], got " + std::to_string(text_scale));
  if (side_size < 64 || side_size > 8192)
    throw InvalidInput("ReportFigureOptions: side_size must be in [64, 8192], got " + std::to_string(side_size));
  if (distance_range_mm && (!(*distance_range_mm > 0) || !std::isfinite(*distance_range_mm)))
    throw InvalidInput("ReportFigureOptions: distance_range_mm must be > 0, got " + std::to_string(*distance_range_mm));
}

render::Rgb report_curve_colour(const std::string& name, size_t index) { return render::drawing_colour(name, index); }

Eigen::VectorXd model_to_scan_distances(const RegisterResult& r) {
  const Points& V = r.fitted_mm.V;
  Eigen::VectorXd d(V.rows());
  if (V.rows() == 0) return d;
  if (r.coverage.distance_mm.size() == static_cast<size_t>(V.rows())) {  // uncovered: NaN, drawn grey
    for (Eigen::Index i = 0; i < V.rows(); ++i)
      d[i] = r.coverage.covered[static_cast<size_t>(i)] ? r.coverage.distance_mm[static_cast<size_t>(i)]
                                                        : std::numeric_limits<double>::quiet_NaN();
    return d;
  }
  const fit::ScanTarget scan(r.scan.mesh_mm, 0);
  const bool skip_border = !r.scan.was_point_cloud;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const fit::ScanMatch m = scan.closest(V.row(i).transpose());
    d[i] = skip_border && m.on_boundary ? std::numeric_limits<double>::quiet_NaN() : std::sqrt(m.sq_dist);
  }
  return d;
}

render::Scene overlay_scene(const RegisterResult& r, const ReportFigureOptions& o) {
  return overlay_scene_with(r, o, overlay_scan(r, body_frame_of(r).body_to_world));
}


double distance_scale_mm(const Eigen::VectorXd& d) {
  std::vector<double> v;
  v.reserve(static_cast<size_t>(d.size()));
  for (Eigen::Index i = 0; i < d.size(); ++i)
    if (std::isfinite(d[i])) v.push_back(d[i]);
  if (v.empty()) return kMinDistanceScaleMm;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(std::ceil(0.95 * static_cast<double>(v.size()))) - 1);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  const double p95 = std::max(v[k], kMinDistanceScaleMm);
  static constexpr std::array<double, 10> kNice = {1, 1.5, 2, 2.5, 3, 4, 5, 6, 8, 10};
  const double decade = std::pow(10.0, std::floor(std::log10(p95)));
  for (double n : kNice)
    if (n * decade >= p95 * (1 - 1e-12)) return n * decade;
  return 10 * decade;
}

render::ScalarField distance_field(const Eigen::VectorXd& distances_mm, double hi_mm) {
  render::ScalarField field;
  field.values = distances_mm;
  field.map = render::Colormap::Viridis;
  field.lo = 0.0;
  field.hi = hi_mm;
  field.units = "mm";
  field.label = "distance";
  return field;
}

render::RenderOptions figure_render_options(const ReportFigureOptions& o, const Eigen::Matrix4d& body_to_world) {
  render::RenderOptions ro;
  ro.width = o.size;
  ro.height = o.size;
  ro.supersample = o.supersample;
  ro.text_scale = o.text_scale;
  ro.body_to_world = body_to_world;
  ro.margin = 0.04;
  return ro;
}

ReportFigures render_report_figures(const RegisterResult& r, const ReportFigureOptions& o) {
  check_result(r, o);
  const mesh::BodyFrame frame = body_frame_of(r);
  TriangleMesh scan = overlay_scan(r, frame.body_to_world);
  const render::Scene scene = overlay_scene_with(r, o, scan);
  ReportFigureOptions side = o;  // the side views' overlays are sized for their smaller images
  side.size = o.side_size;
  const render::Scene side_scene = overlay_scene_with(r, side, std::move(scan));  // two copies of the scan, not three
  // Framed by everything in the scene, as render_scene does.
  return render_figures(r, o, frame, scene, side_scene, [&](size_t k, const render::Scene& s) {
    return render::draw_scene_meshes(s, overlay_render_options(k, o, frame.body_to_world));
  });
}

ReportFigures render_report_figures(const RegisterResult& r, const ReportLayers& layers, const ReportFigureOptions& o) {
  return render_over_layers(r, layers.frame, o, [&](size_t k) { return draw_report_layer(layers, k, o); });
}

ReportFigures report_figures(const RegisterResult& r, const model::RiggedModel& model, const ReportFigureOptions& o,
                             const std::shared_ptr<ReportLayerDrawing>& drawing) {
  if (drawing) {
    const ReportLayers* layers = drawing->layers();
    if (layers) {
      const ReportFigureOptions& d = drawing->options();
      if (d.size != o.size || d.side_size != o.side_size || d.supersample != o.supersample || d.text_scale != o.text_scale)
        throw InvalidInput("report_figures: the scan layers were drawn with other figure sizes");
      return render_over_layers(r, layers->frame, o, [&](size_t k) { return drawing->take(k); }, true);
    }
  } else if (std::optional<ReportLayers> planned = plan_report_layers(r, model, o)) {
    return render_report_figures(r, *planned, o);
  }
  return render_report_figures(r, o);
}

}  // namespace breastfit::pipeline
