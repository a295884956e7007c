#include "breastfit/synth/synth_case.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/core/rng.h"
#include "breastfit/mesh/boundary.h"
#include "breastfit/mesh/cleanup.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/model/pose_evaluator.h"
#include "breastfit/spatial/closest_point_index.h"
#include "breastfit/synth/camera_rig.h"
#include "breastfit/synth/scan_defects.h"
#include "breastfit/mesh/subdivision.h"
#include "breastfit/synth/subject_pose.h"
#include "breastfit/synth/truth_curves.h"

namespace breastfit::synth {
namespace {

using json = nlohmann::ordered_json;
constexpr double kDeg = std::numbers::pi / 180.0;

/// Independent random stream per stage, so that e.g. changing the number of holes does not
/// change the subject.
Rng stage_rng(std::uint64_t seed, std::uint64_t stage) {
  return Rng(seed * 0x9E3779B97F4A7C15ull + stage * 0xD1B54A32D192ED03ull + 0x5851F42D4C957F2Dull);
}

Vec3 random_unit(Rng& rng) {
  for (;;) {
    const Vec3 v(rng.normal(), rng.normal(), rng.normal());
    if (v.norm() > 1e-6) return v.normalized();
  }
}

Vec3 blended_normal(const Points& N, const Triangles& F, const SurfacePoint& p) {
  Vec3 n = Vec3::Zero();
  for (int k = 0; k < 3; ++k) n += p.bary[k] * N.row(F(p.face, k)).transpose();
  return n.norm() > 1e-12 ? Vec3(n.normalized()) : Vec3::UnitZ();
}

/// Rounds for readable JSON (values are reported, not used for computation).
double r6(double x) { return std::round(x * 1e6) / 1e6; }
double r3(double x) { return std::round(x * 1e3) / 1e3; }
json vec_json(const Vec3& v, double (*round)(double) = r6) { return json::array({round(v.x()), round(v.y()), round(v.z())}); }

json range_json(const Range& r) { return json::array({r.lo, r.hi}); }

json similarity_json(const model::Similarity& s) {
  const Quat q = s.rotation.normalized();
  return json{{"rotation_wxyz", json::array({q.w(), q.x(), q.y(), q.z()})},
              {"translation_mm", json::array({s.translation.x(), s.translation.y(), s.translation.z()})},
              {"scale", s.scale}};
}

json params_json(const model::RiggedModel& model, const model::PoseParams& p) {
  json bones = json::object();
  for (int j = 0; j < model.num_bones(); ++j) {
    const auto& b = p.bones[static_cast<size_t>(j)];
    const Eigen::AngleAxisd aa(b.rotation.normalized());
    const Vec3 rv = aa.axis() * aa.angle() / kDeg;
    bones[model.bones[static_cast<size_t>(j)].name] =
        json{{"rotation_wxyz", json::array({b.rotation.w(), b.rotation.x(), b.rotation.y(), b.rotation.z()})},
             {"rotation_vector_deg", json::array({rv.x(), rv.y(), rv.z()})},
             {"translation_mm", json::array({b.translation.x(), b.translation.y(), b.translation.z()})},
             {"scale", json::array({b.scale.x(), b.scale.y(), b.scale.z()})}};
  }
  json shapes = json::object();
  for (int k = 0; k < model.num_blendshapes(); ++k) shapes[model.blendshapes[static_cast<size_t>(k)].name] = p.alpha[k];
  return json{{"global", similarity_json(p.global)}, {"bones", bones}, {"blendshapes", shapes}};
}

/// Scanner axes before the misalignment, as a rotation body -> scanner.
Mat3 base_orientation(PoseType pose) {
  Mat3 R;
  if (pose == PoseType::Standing)
    R << 1, 0, 0,  //  X = patient left
        0, 0, 1,   //  Y = up (superior)
        0, -1, 0;  //  Z = anterior (towards the operator)
  else
    R << 1, 0, 0,  //  X = patient left
        0, -1, 0,  //  Y = anterior (up, away from the table)
        0, 0, -1;  //  Z = inferior (towards the feet)
  return R;
}

}  // namespace

std::string default_case_id(const SynthOptions& options) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "synth_%03llu_%s", static_cast<unsigned long long>(options.seed),
                std::string(pose_type_name(options.pose)).c_str());
  return buf;
}

SynthCase make_case(const model::RiggedModel& model, const SynthOptions& options) {
  options.validate();
  model.validate();
  const bool supine = options.pose == PoseType::Supine;
  SynthCase out;
  out.id = options.case_id.empty() ? default_case_id(options) : options.case_id;
  out.units = options.units;
  out.scale_mm_to_file_units = options.units == "m" ? 1e-3 : 1.0;

  // ---- subject ----
  Rng rng_subject = stage_rng(options.seed, 1);
  const SubjectPose subject = sample_subject_pose(model, options, rng_subject);
  out.true_params = subject.params;
  TriangleMesh truth;
  truth.V = model::pose_vertices(model, subject.params);
  truth.F = model.rest.F;

  // ---- refinement (surface points follow) ----
  std::vector<SurfacePoint> lm_sp;
  for (const auto& l : model.landmarks) lm_sp.push_back(l.point);
  std::vector<std::vector<SurfacePoint>> dr_sp;
  for (const auto& d : model.drawings) dr_sp.push_back(d.points);
  const double coarse_edge = mesh::median_edge_length(truth);
  int steps = 0;
  while (steps < options.refinement.max_steps && mesh::median_edge_length(truth) > options.refinement.target_edge_mm &&
         static_cast<double>(truth.num_faces()) * 4.0 <= options.refinement.max_faces) {
    truth = mesh::subdivide(truth, options.refinement.loop);
    for (auto& p : lm_sp) p = mesh::refine_surface_point(p);
    for (auto& d : dr_sp)
      for (auto& p : d) p = mesh::refine_surface_point(p);
    ++steps;
  }
  const double dense_edge = mesh::median_edge_length(truth);

  // ---- smooth deformation outside the model's space ----
  Rng rng_deform = stage_rng(options.seed, 2);
  json bumps_json = json::array();
  {
    const Points N0 = mesh::vertex_normals(truth);
    const Index nv = truth.num_vertices();
    Eigen::VectorXd disp = Eigen::VectorXd::Zero(nv);
    for (int b = 0; b < options.deformation.n_bumps; ++b) {
      const Index c = static_cast<Index>(rng_deform.below(static_cast<std::uint64_t>(nv)));
      const double sign = rng_deform.uniform() < 0.5 ? -1.0 : 1.0;
      const double amp = sign * rng_deform.uniform(options.deformation.amplitude_mm.lo, options.deformation.amplitude_mm.hi);
      const double width = rng_deform.uniform(options.deformation.width_mm.lo, options.deformation.width_mm.hi);
      const double sigma = 0.5 * width;
      const Vec3 centre = truth.V.row(c).transpose();
      for (Index v = 0; v < nv; ++v) {
        const double d2 = (truth.V.row(v).transpose() - centre).squaredNorm();
        if (d2 < 16.0 * sigma * sigma) disp[v] += amp * std::exp(-d2 / (2.0 * sigma * sigma));
      }
      bumps_json.push_back(json{{"center_body_mm", vec_json(centre, r3)}, {"amplitude_mm", r3(amp)}, {"width_mm", r3(width)}});
    }
    for (Index v = 0; v < nv; ++v) truth.V.row(v) += disp[v] * N0.row(v);
  }
  const Points N = mesh::vertex_normals(truth);

  // ---- truth landmarks and curves (body frame) ----
  std::vector<Vec3> lm_body;
  for (size_t i = 0; i < lm_sp.size(); ++i) {
    const Vec3 p = lm_sp[i].position(truth.V, truth.F);
    lm_body.push_back(p);
    out.truth_landmarks_body.push_back({model.landmarks[i].name, p});
  }
  const spatial::ClosestPointIndex truth_index(truth);
  std::vector<Curve> curves_body;
  for (size_t i = 0; i < dr_sp.size(); ++i) {
    if (dr_sp[i].size() < 2) continue;
    Points P(static_cast<Index>(dr_sp[i].size()), 3);
    for (size_t k = 0; k < dr_sp[i].size(); ++k) P.row(static_cast<Index>(k)) = dr_sp[i][k].position(truth.V, truth.F).transpose();
    Curve c;
    c.name = model.drawings[i].name;
    c.closed = model.drawings[i].closed;
    c.points = resample_on_surface(P, c.closed, truth_index, 1.0);
    curves_body.push_back(std::move(c));
  }

  // ---- scanner: visibility ----
  const Vec3 centre = 0.5 * (truth.V.colwise().minCoeff() + truth.V.colwise().maxCoeff()).transpose();
  const std::vector<Camera> cams = camera_rig(options.scanner, options.pose, centre);
  const std::vector<int> views = count_views(truth, N, cams, options.scanner, options.scanner.min_views);
  TriangleMesh scan;
  scan.V = truth.V;
  scan.N = N;
  {
    std::vector<Index> keep;
    for (Index f = 0; f < truth.num_faces(); ++f) {
      bool seen = true;
      for (int k = 0; k < 3; ++k) seen = seen && views[static_cast<size_t>(truth.F(f, k))] >= options.scanner.min_views;
      if (seen) keep.push_back(f);
    }
    scan.F.resize(static_cast<Index>(keep.size()), 3);
    for (size_t i = 0; i < keep.size(); ++i) scan.F.row(static_cast<Index>(i)) = truth.F.row(keep[i]);
  }
  const Index visible_faces = scan.num_faces();

  // ---- defects: holes, small components, noise ----
  Rng rng_holes = stage_rng(options.seed, 3);
  const std::vector<Hole> holes = punch_holes(scan, lm_body, options.artifacts, rng_holes);
  mesh::CleanupOptions co;
  co.remove_degenerate = false;
  co.remove_small_components = true;
  co.min_component_faces = options.artifacts.min_component_faces;
  const mesh::CleanupSummary cs = mesh::cleanup(scan, co);
  if (scan.num_faces() == 0)
    throw InvalidInput("synth: the simulated scan is empty (no part of the surface is seen by the cameras)");
  const Eigen::VectorXd truth_areas = mesh::face_areas(truth);
  const double observed_area_fraction = mesh::face_areas(scan).sum() / std::max(truth_areas.sum(), 1e-12);
  const Points scan_N = scan.N;
  Rng rng_noise = stage_rng(options.seed, 4);
  add_scan_noise(scan.V, scan_N, options.artifacts, rng_noise);
  scan.N.resize(0, 3);
  TriangleMesh body_scan = scan;
  const Index body_vertices = body_scan.num_vertices(), body_faces = body_scan.num_faces();
  const auto loops = mesh::boundary_loops(body_scan);

  Rng rng_frag = stage_rng(options.seed, 5);
  std::vector<Fragment> fragments;
  append_mesh(scan, make_fragments(body_scan, scan_N, options.artifacts, rng_frag, fragments));
  json table_json = nullptr;
  if (supine && options.artifacts.table_strip) {
    const TriangleMesh table = make_table_strips(truth.V, rng_frag);
    append_mesh(scan, table);
    table_json = json{{"faces", table.num_faces()}, {"y_body_mm", r3(table.num_vertices() ? table.V(0, 1) : 0.0)}};
  }

  // ---- annotated input landmarks: tangential noise, snapped to the noisy scan ----
  Rng rng_lm = stage_rng(options.seed, 7);
  const spatial::ClosestPointIndex scan_index(body_scan);
  std::vector<Vec3> input_body;
  for (size_t i = 0; i < lm_sp.size(); ++i) {
    const Vec3 n = blended_normal(N, truth.F, lm_sp[i]);
    const Vec3 a = std::abs(n.x()) < 0.8 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 t1 = n.cross(a).normalized(), t2 = n.cross(t1).normalized();
    const Vec3 offset = options.landmark_noise_mm * (rng_lm.normal() * t1 + rng_lm.normal() * t2);
    const Vec3 noisy = lm_body[i] + offset;
    const spatial::ClosestPoint cp = scan_index.closest(noisy);
    input_body.push_back(cp.point);
    out.input_landmark_errors.push_back(
        {model.landmarks[i].name, (cp.point - lm_body[i]).norm(), std::sqrt(cp.sq_dist), offset.norm()});
  }

  // ---- rigid misalignment and units ----
  Rng rng_mis = stage_rng(options.seed, 6);
  const Vec3 rot_axis = random_unit(rng_mis);
  const double rot_deg = rng_mis.uniform(0.0, options.misalign_rotation_deg);
  const Vec3 trans_dir = random_unit(rng_mis);
  const double trans_mm = rng_mis.uniform(0.0, options.misalign_translation_m * 1000.0);
  const Mat3 R = Eigen::AngleAxisd(rot_deg * kDeg, rot_axis).toRotationMatrix() * base_orientation(options.pose);
  const Vec3 t = -(R * centre) + trans_mm * trans_dir;
  out.T_body_to_scan_mm.setIdentity();
  out.T_body_to_scan_mm.topLeftCorner<3, 3>() = R;
  out.T_body_to_scan_mm.topRightCorner<3, 1>() = t;
  const double s = out.scale_mm_to_file_units;
  auto to_file = [&](const Vec3& x) -> Vec3 { return s * (R * x + t); };
  auto points_to_file = [&](const Points& P) {
    Points Q(P.rows(), 3);
    for (Index i = 0; i < P.rows(); ++i) Q.row(i) = to_file(P.row(i).transpose()).transpose();
    return Q;
  };
  out.scan.V = points_to_file(scan.V);
  out.scan.F = scan.F;
  out.truth_surface.V = points_to_file(truth.V);
  out.truth_surface.F = truth.F;
  for (size_t i = 0; i < lm_body.size(); ++i) {
    out.truth_landmarks.push_back({model.landmarks[i].name, to_file(lm_body[i])});
    out.input_landmarks.push_back({model.landmarks[i].name, to_file(input_body[i])});
  }
  for (const Curve& c : curves_body) out.truth_curves.push_back({c.name, c.closed, points_to_file(c.points)});
  model::Similarity T_sim;
  T_sim.rotation = Quat(R);
  T_sim.translation = t;
  out.true_params_scan = out.true_params;
  out.true_params_scan.global = T_sim.compose(out.true_params.global);

  // ---- meta.json ----
  json meta;
  json T = json::array();
  for (int r = 0; r < 4; ++r) {
    json row = json::array();
    for (int c = 0; c < 4; ++c) row.push_back(out.T_body_to_scan_mm(r, c));
    T.push_back(row);
  }
  meta["T_body_to_scan_mm"] = T;
  meta["body_frame"] = "LPS, right-handed: x = patient left, y = posterior, z = superior; mm. Anterior is -y.";
  json curve_lengths = json::object();
  for (const Curve& c : curves_body) curve_lengths[c.name] = r3(c.length());
  json arms_abd = json::object(), arms_flex = json::object();
  for (const ArmPose& a : subject.arms) {
    arms_abd[a.side] = r3(a.abduction_deg);
    arms_flex[a.side] = r3(a.flexion_deg);
  }
  meta["derived"] = json{{"curve_lengths_mm", curve_lengths}, {"arm_abduction_deg_posed", arms_abd}};
  meta["deformation"] = json{{"bumps", bumps_json}};
  meta["generation_time_s"] = nullptr;
  meta["generator_version"] = kGeneratorVersion;
  meta["id"] = out.id;
  json input_lm = json::object();
  for (const auto& e : out.input_landmark_errors)
    input_lm[e.name] = json{{"error_vs_truth_mm", r3(e.error_vs_truth_mm)},
                            {"snap_distance_mm", r3(e.snap_distance_mm)},
                            {"tangential_offset_mm", r3(e.tangential_offset_mm)}};
  meta["input_landmarks"] = input_lm;
  meta["misalignment"] = json{
      {"base_orientation",
       "standing: X=left, Y=up, Z=anterior (towards the operator); supine: X=left, Y=anterior (up, away from the "
       "table), Z=inferior"},
      {"rotation_axis", vec_json(rot_axis)},
      {"rotation_deg", r6(rot_deg)},
      {"translation_mm", r3(trans_mm)},
      {"translation_dir", vec_json(trans_dir)},
      {"body_centre_mm", vec_json(centre, r3)}};
  json arms = json::object();
  for (const ArmPose& a : subject.arms)
    arms[a.side] = json{{"rest_abduction_deg", r3(a.rest_abduction_deg)},
                        {"abduction_deg", r3(a.abduction_deg)},
                        {"flexion_deg", r3(a.flexion_deg)}};
  meta["pose"] = json{{"type", std::string(pose_type_name(options.pose))},
                      {"arms", arms},
                      {"arm_flexion_deg", arms_flex},
                      {"shoulder_share", options.subject.shoulder_share},
                      {"supine_shift", options.subject.supine_shift},
                      {"supine_shapes", subject.supine_shapes}};
  meta["scale_mm_to_file_units"] = s;
  char frame[128];
  std::snprintf(frame, sizeof frame, "x_file = s * (R @ x_body + t), s = %g (file units per mm)", s);
  meta["scan_frame"] = frame;
  const auto& sc = options.scanner;
  const auto& ar = options.artifacts;
  meta["scan_params"] = json{
      {"arc_deg", supine ? sc.arc_deg_supine : sc.arc_deg_standing},
      {"distance_m", sc.distance_mm / 1000.0},
      {"elevations_deg", sc.elevations_deg},
      {"fov_deg", json::array({sc.fov_horizontal_deg, sc.fov_vertical_deg})},
      {"hole_landmark_clearance_mm", ar.hole_landmark_clearance_mm},
      {"hole_radius_mm", range_json(ar.hole_radius_mm)},
      {"landmark_noise_mm", options.landmark_noise_mm},
      {"lowfreq_noise_mm", ar.lowfreq_noise_mm},
      {"lowfreq_wavelength_mm", range_json(ar.lowfreq_wavelength_mm)},
      {"max_incidence_deg", sc.max_incidence_deg},
      {"min_component_faces", ar.min_component_faces},
      {"min_views", sc.min_views},
      {"misalign_rot_deg", options.misalign_rotation_deg},
      {"misalign_trans_m", options.misalign_translation_m},
      {"n_azimuth", sc.n_azimuth},
      {"n_fragments", ar.n_fragments},
      {"fragment_distance_mm", range_json(ar.fragment_distance_mm)},
      {"fragment_radius_mm", range_json(ar.fragment_radius_mm)},
      {"n_holes", ar.n_holes},
      {"subdiv", steps},
      {"subdivision", options.refinement.loop ? "loop" : "midpoint"},
      {"refinement_target_edge_mm", options.refinement.target_edge_mm},
      {"refinement_max_steps", options.refinement.max_steps},
      {"refinement_max_faces", options.refinement.max_faces},
      {"table_fragment", supine && ar.table_strip},
      {"tangential_jitter_mm", ar.tangential_jitter_mm},
      {"units", options.units},
      {"white_noise_mm", ar.white_noise_mm}};
  json holes_json = json::array();
  for (const Hole& h : holes) holes_json.push_back(json{{"center_body_mm", vec_json(h.centre, r3)}, {"radius_mm", r3(h.radius_mm)}});
  json frags_json = json::array();
  for (const Fragment& f : fragments)
    frags_json.push_back(json{{"center_body_mm", vec_json(f.centre, r3)},
                              {"radius_mm", r3(f.radius_mm)},
                              {"distance_mm", r3(f.distance_mm)},
                              {"type", "patch"}});
  meta["scan_stats"] = json{{"boundary_loops", loops.size()},
                            {"coarse_edge_mm_median", r3(coarse_edge)},
                            {"dense_edge_mm_median", r3(dense_edge)},
                            {"fragments", frags_json},
                            {"holes", holes_json},
                            {"n_views", cams.size()},
                            {"observed_area_fraction", r6(observed_area_fraction)},
                            {"removed_components", cs.removed_components},
                            {"scan_body_faces", body_faces},
                            {"scan_body_vertices", body_vertices},
                            {"scan_faces", out.scan.num_faces()},
                            {"scan_vertices", out.scan.num_vertices()},
                            {"table", table_json},
                            {"truth_faces", out.truth_surface.num_faces()},
                            {"truth_vertices", out.truth_surface.num_vertices()},
                            {"visible_faces", visible_faces}};
  meta["seed"] = options.seed;
  meta["source"] = "breastfit synth: rigged template '" + model.name + "' posed with random parameters";
  json subject_json = json{{"template", model.name},
                           {"shape_amplitude", options.subject.shape_amplitude},
                           {"global_scale_range", options.subject.global_scale_range},
                           {"bone_scale_range", options.subject.bone_scale_range},
                           {"bone_rotation_deg", options.subject.bone_rotation_deg},
                           {"standing_abduction_deg", range_json(options.subject.standing_abduction_deg)},
                           {"supine_abduction_deg", range_json(options.subject.supine_abduction_deg)},
                           {"standing_flexion_deg", range_json(options.subject.standing_flexion_deg)},
                           {"supine_flexion_deg", range_json(options.subject.supine_flexion_deg)},
                           {"deformation_bumps", options.deformation.n_bumps},
                           {"deformation_amplitude_mm", range_json(options.deformation.amplitude_mm)},
                           {"deformation_width_mm", range_json(options.deformation.width_mm)}};
  meta["subject"] = subject_json;
  meta["true_params"] = params_json(model, out.true_params);
  meta["true_params"]["frame"] = "body (LPS mm); global similarity = subject scale only";
  meta["true_global_scan_mm"] = similarity_json(out.true_params_scan.global);
  meta["true_global_scan_mm"]["frame"] = "scanner frame, mm (T_body_to_scan_mm composed with the body-frame global)";
  meta["units"] = options.units;
  out.meta_json = meta.dump(1) + "\n";
  return out;
}

}  // namespace breastfit::synth
