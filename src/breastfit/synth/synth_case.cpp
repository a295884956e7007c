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

// ---- the steps of make_case, in order ----------------------------------------------------

/// The posed subject refined towards the target edge length, with the model's landmarks and
/// drawings followed through the subdivisions as surface points.
struct RefinedTruth {
  TriangleMesh mesh;
  std::vector<SurfacePoint> landmarks;              ///< per model landmark
  std::vector<std::vector<SurfacePoint>> drawings;  ///< per model drawing
  int steps = 0;                                    ///< subdivisions applied
  double coarse_edge = 0;                           ///< median edge before, mm
  double dense_edge = 0;                            ///< median edge after, mm
};

RefinedTruth refined_truth(const model::RiggedModel& model, const model::PoseParams& params,
                           const RefinementOptions& o) {
  RefinedTruth r;
  r.mesh.V = model::pose_vertices(model, params);
  r.mesh.F = model.rest.F;
  for (const auto& l : model.landmarks) r.landmarks.push_back(l.point);
  for (const auto& d : model.drawings) r.drawings.push_back(d.points);
  r.coarse_edge = mesh::median_edge_length(r.mesh);
  while (r.steps < o.max_steps && mesh::median_edge_length(r.mesh) > o.target_edge_mm &&
         static_cast<double>(r.mesh.num_faces()) * 4.0 <= o.max_faces) {
    r.mesh = mesh::subdivide(r.mesh, o.loop);
    for (auto& p : r.landmarks) p = mesh::refine_surface_point(p);
    for (auto& d : r.drawings)
      for (auto& p : d) p = mesh::refine_surface_point(p);
    ++r.steps;
  }
  r.dense_edge = mesh::median_edge_length(r.mesh);
  return r;
}

/// Smooth deformation outside the model's space: Gaussian bumps along the normals.
/// \return the bumps, for meta.json
json add_bumps(TriangleMesh& truth, const DeformationOptions& o, Rng& rng) {
  json bumps = json::array();
  const Points N0 = mesh::vertex_normals(truth);
  const Index nv = truth.num_vertices();
  Eigen::VectorXd disp = Eigen::VectorXd::Zero(nv);
  for (int b = 0; b < o.n_bumps; ++b) {
    const Index c = static_cast<Index>(rng.below(static_cast<std::uint64_t>(nv)));
    const double sign = rng.uniform() < 0.5 ? -1.0 : 1.0;
    const double amp = sign * rng.uniform(o.amplitude_mm.lo, o.amplitude_mm.hi);
    const double width = rng.uniform(o.width_mm.lo, o.width_mm.hi);
    const double sigma = 0.5 * width;
    const Vec3 centre = truth.V.row(c).transpose();
    for (Index v = 0; v < nv; ++v) {
      const double d2 = (truth.V.row(v).transpose() - centre).squaredNorm();
      if (d2 < 16.0 * sigma * sigma) disp[v] += amp * std::exp(-d2 / (2.0 * sigma * sigma));
    }
    bumps.push_back(json{{"center_body_mm", vec_json(centre, r3)}, {"amplitude_mm", r3(amp)}, {"width_mm", r3(width)}});
  }
  for (Index v = 0; v < nv; ++v) truth.V.row(v) += disp[v] * N0.row(v);
  return bumps;
}

/// The drawings with at least 2 points as curves on the truth surface (~1 mm spacing), body frame.
std::vector<Curve> truth_curves_body(const model::RiggedModel& model, const RefinedTruth& truth) {
  const TriangleMesh& m = truth.mesh;
  const spatial::ClosestPointIndex truth_index(m);
  std::vector<Curve> curves;
  for (size_t i = 0; i < truth.drawings.size(); ++i) {
    const auto& d = truth.drawings[i];
    if (d.size() < 2) continue;
    Points P(static_cast<Index>(d.size()), 3);
    for (size_t k = 0; k < d.size(); ++k) P.row(static_cast<Index>(k)) = d[k].position(m.V, m.F).transpose();
    Curve c;
    c.name = model.drawings[i].name;
    c.closed = model.drawings[i].closed;
    c.points = resample_on_surface(P, c.closed, truth_index, 1.0);
    curves.push_back(std::move(c));
  }
  return curves;
}

/// The triangles of the truth every vertex of which is seen by at least min_views cameras;
/// V and N are the truth's.
TriangleMesh visible_part(const TriangleMesh& truth, const Points& N, const std::vector<Camera>& cams,
                          const ScannerOptions& o) {
  const std::vector<int> views = count_views(truth, N, cams, o, o.min_views);
  TriangleMesh scan;
  scan.V = truth.V;
  scan.N = N;
  std::vector<Index> keep;
  for (Index f = 0; f < truth.num_faces(); ++f) {
    bool seen = true;
    for (int k = 0; k < 3; ++k) seen = seen && views[static_cast<size_t>(truth.F(f, k))] >= o.min_views;
    if (seen) keep.push_back(f);
  }
  scan.F.resize(static_cast<Index>(keep.size()), 3);
  for (size_t i = 0; i < keep.size(); ++i) scan.F.row(static_cast<Index>(i)) = truth.F.row(keep[i]);
  return scan;
}

/// The simulated scan (body frame) and what was done to make it.
struct SimulatedScan {
  TriangleMesh scan;             ///< body + fragments (+ table)
  TriangleMesh body;             ///< the noisy body part alone
  size_t n_views = 0;
  Index visible_faces = 0;
  std::vector<Hole> holes;
  mesh::CleanupSummary cleanup;
  double observed_area_fraction = 0;
  size_t boundary_loops = 0;     ///< of the body part
  std::vector<Fragment> fragments;
  json table = nullptr;          ///< the table strips (supine), or null
};

/// Defects of the visible part: holes away from the landmarks, small pieces removed, noise.
void add_body_defects(const TriangleMesh& truth, const std::vector<Vec3>& landmarks, const SynthOptions& options,
                      SimulatedScan& sim, Points& scan_N) {
  TriangleMesh& scan = sim.scan;
  Rng rng_holes = stage_rng(options.seed, 3);
  sim.holes = punch_holes(scan, landmarks, options.artifacts, rng_holes);
  mesh::CleanupOptions co;
  co.remove_degenerate = false;
  co.remove_small_components = true;
  co.min_component_faces = options.artifacts.min_component_faces;
  sim.cleanup = mesh::cleanup(scan, co);
  if (scan.num_faces() == 0)
    throw InvalidInput("synth: the simulated scan is empty (no part of the surface is seen by the cameras)");
  const Eigen::VectorXd truth_areas = mesh::face_areas(truth);
  sim.observed_area_fraction = mesh::face_areas(scan).sum() / std::max(truth_areas.sum(), 1e-12);
  scan_N = scan.N;
  Rng rng_noise = stage_rng(options.seed, 4);
  add_scan_noise(scan.V, scan_N, options.artifacts, rng_noise);
  scan.N.resize(0, 3);
}

/// Scanner simulation: what the cameras see, defects, floating fragments and (supine) the table.
SimulatedScan simulate_scan(const TriangleMesh& truth, const Points& N, const std::vector<Vec3>& landmarks,
                            const Vec3& centre, const SynthOptions& options) {
  SimulatedScan sim;
  const std::vector<Camera> cams = camera_rig(options.scanner, options.pose, centre);
  sim.n_views = cams.size();
  sim.scan = visible_part(truth, N, cams, options.scanner);
  sim.visible_faces = sim.scan.num_faces();
  Points scan_N;
  add_body_defects(truth, landmarks, options, sim, scan_N);
  sim.body = sim.scan;
  sim.boundary_loops = mesh::boundary_loops(sim.body).size();
  Rng rng_frag = stage_rng(options.seed, 5);
  append_mesh(sim.scan, make_fragments(sim.body, scan_N, options.artifacts, rng_frag, sim.fragments));
  if (options.pose == PoseType::Supine && options.artifacts.table_strip) {
    const TriangleMesh table = make_table_strips(truth.V, rng_frag);
    append_mesh(sim.scan, table);
    sim.table = json{{"faces", table.num_faces()}, {"y_body_mm", r3(table.num_vertices() ? table.V(0, 1) : 0.0)}};
  }
  return sim;
}

/// Annotated input landmarks: the truth moved by tangential noise, snapped to the noisy body
/// scan (body frame); their errors go to out.input_landmark_errors.
std::vector<Vec3> input_landmarks_body(const model::RiggedModel& model, const RefinedTruth& truth, const Points& N,
                                       const std::vector<Vec3>& lm_body, const TriangleMesh& body_scan,
                                       const SynthOptions& options, SynthCase& out) {
  Rng rng_lm = stage_rng(options.seed, 7);
  const spatial::ClosestPointIndex scan_index(body_scan);
  std::vector<Vec3> input_body;
  for (size_t i = 0; i < truth.landmarks.size(); ++i) {
    const Vec3 n = blended_normal(N, truth.mesh.F, truth.landmarks[i]);
    const Vec3 a = std::abs(n.x()) < 0.8 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 t1 = n.cross(a).normalized(), t2 = n.cross(t1).normalized();
    const Vec3 offset = options.landmark_noise_mm * (rng_lm.normal() * t1 + rng_lm.normal() * t2);
    const Vec3 noisy = lm_body[i] + offset;
    const spatial::ClosestPoint cp = scan_index.closest(noisy);
    input_body.push_back(cp.point);
    out.input_landmark_errors.push_back(
        {model.landmarks[i].name, (cp.point - lm_body[i]).norm(), std::sqrt(cp.sq_dist), offset.norm()});
  }
  return input_body;
}

/// The random rigid misalignment body -> scanner (before units).
struct Misalignment {
  Vec3 rot_axis = Vec3::UnitZ();
  double rot_deg = 0;
  Vec3 trans_dir = Vec3::UnitX();
  double trans_mm = 0;
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
};

Misalignment sample_misalignment(const SynthOptions& options, const Vec3& centre) {
  Rng rng_mis = stage_rng(options.seed, 6);
  Misalignment m;
  m.rot_axis = random_unit(rng_mis);
  m.rot_deg = rng_mis.uniform(0.0, options.misalign_rotation_deg);
  m.trans_dir = random_unit(rng_mis);
  m.trans_mm = rng_mis.uniform(0.0, options.misalign_translation_m * 1000.0);
  m.R = Eigen::AngleAxisd(m.rot_deg * kDeg, m.rot_axis).toRotationMatrix() * base_orientation(options.pose);
  m.t = -(m.R * centre) + m.trans_mm * m.trans_dir;
  return m;
}

/// The case's outputs in the scanner frame and file units: scan, truth surface, landmarks,
/// curves, T_body_to_scan_mm and the parameters composed with it.
void to_scanner_frame(const Misalignment& mis, const model::RiggedModel& model, const TriangleMesh& scan,
                      const TriangleMesh& truth, const std::vector<Vec3>& lm_body, const std::vector<Vec3>& input_body,
                      const std::vector<Curve>& curves_body, SynthCase& out) {
  const Mat3& R = mis.R;
  const Vec3& t = mis.t;
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
}

// ---- meta.json --------------------------------------------------------------------------

/// What meta.json reports besides the options and the case's outputs.
struct GenerationRecord {
  const SubjectPose* subject = nullptr;
  const RefinedTruth* truth = nullptr;
  const SimulatedScan* sim = nullptr;
  const Misalignment* mis = nullptr;
  const std::vector<Curve>* curves_body = nullptr;
  json bumps;
  Vec3 centre = Vec3::Zero();
};

json misalignment_json(const GenerationRecord& r) {
  const Misalignment& m = *r.mis;
  return json{{"base_orientation",
               "standing: X=left, Y=up, Z=anterior (towards the operator); supine: X=left, Y=anterior (up, away "
               "from the table), Z=inferior"},
              {"rotation_axis", vec_json(m.rot_axis)},
              {"rotation_deg", r6(m.rot_deg)},
              {"translation_mm", r3(m.trans_mm)},
              {"translation_dir", vec_json(m.trans_dir)},
              {"body_centre_mm", vec_json(r.centre, r3)}};
}

json pose_json(const SynthOptions& options, const SubjectPose& subject) {
  json arms = json::object(), arms_flex = json::object();
  for (const ArmPose& a : subject.arms) {
    arms[a.side] = json{{"rest_abduction_deg", r3(a.rest_abduction_deg)},
                        {"abduction_deg", r3(a.abduction_deg)},
                        {"flexion_deg", r3(a.flexion_deg)}};
    arms_flex[a.side] = r3(a.flexion_deg);
  }
  return json{{"type", std::string(pose_type_name(options.pose))},
              {"arms", arms},
              {"arm_flexion_deg", arms_flex},
              {"shoulder_share", options.subject.shoulder_share},
              {"supine_shift", options.subject.supine_shift},
              {"supine_shapes", subject.supine_shapes}};
}

json scan_params_json(const SynthOptions& options, int steps) {
  const bool supine = options.pose == PoseType::Supine;
  const auto& sc = options.scanner;
  const auto& ar = options.artifacts;
  return json{{"arc_deg", supine ? sc.arc_deg_supine : sc.arc_deg_standing},
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
}

json scan_stats_json(const GenerationRecord& r, const SynthCase& out) {
  const SimulatedScan& sim = *r.sim;
  json holes = json::array();
  for (const Hole& h : sim.holes) holes.push_back(json{{"center_body_mm", vec_json(h.centre, r3)}, {"radius_mm", r3(h.radius_mm)}});
  json frags = json::array();
  for (const Fragment& f : sim.fragments)
    frags.push_back(json{{"center_body_mm", vec_json(f.centre, r3)},
                         {"radius_mm", r3(f.radius_mm)},
                         {"distance_mm", r3(f.distance_mm)},
                         {"type", "patch"}});
  return json{{"boundary_loops", sim.boundary_loops},
              {"coarse_edge_mm_median", r3(r.truth->coarse_edge)},
              {"dense_edge_mm_median", r3(r.truth->dense_edge)},
              {"fragments", frags},
              {"holes", holes},
              {"n_views", sim.n_views},
              {"observed_area_fraction", r6(sim.observed_area_fraction)},
              {"removed_components", sim.cleanup.removed_components},
              {"scan_body_faces", sim.body.num_faces()},
              {"scan_body_vertices", sim.body.num_vertices()},
              {"scan_faces", out.scan.num_faces()},
              {"scan_vertices", out.scan.num_vertices()},
              {"table", sim.table},
              {"truth_faces", out.truth_surface.num_faces()},
              {"truth_vertices", out.truth_surface.num_vertices()},
              {"visible_faces", sim.visible_faces}};
}

json subject_json(const model::RiggedModel& model, const SynthOptions& options) {
  const auto& so = options.subject;
  const auto& d = options.deformation;
  return json{{"template", model.name},
              {"shape_amplitude", so.shape_amplitude},
              {"global_scale_range", so.global_scale_range},
              {"bone_scale_range", so.bone_scale_range},
              {"bone_rotation_deg", so.bone_rotation_deg},
              {"standing_abduction_deg", range_json(so.standing_abduction_deg)},
              {"supine_abduction_deg", range_json(so.supine_abduction_deg)},
              {"standing_flexion_deg", range_json(so.standing_flexion_deg)},
              {"supine_flexion_deg", range_json(so.supine_flexion_deg)},
              {"deformation_bumps", d.n_bumps},
              {"deformation_amplitude_mm", range_json(d.amplitude_mm)},
              {"deformation_width_mm", range_json(d.width_mm)}};
}

/// truth/meta.json: everything needed to reproduce and to interpret the case (keys in order).
std::string meta_json(const model::RiggedModel& model, const SynthOptions& options, const GenerationRecord& r,
                      const SynthCase& out) {
  json meta;
  json T = json::array();
  for (int i = 0; i < 4; ++i) {
    json row = json::array();
    for (int c = 0; c < 4; ++c) row.push_back(out.T_body_to_scan_mm(i, c));
    T.push_back(row);
  }
  meta["T_body_to_scan_mm"] = T;
  meta["body_frame"] = "LPS, right-handed: x = patient left, y = posterior, z = superior; mm. Anterior is -y.";
  json curve_lengths = json::object();
  for (const Curve& c : *r.curves_body) curve_lengths[c.name] = r3(c.length());
  json arms_abd = json::object();
  for (const ArmPose& a : r.subject->arms) arms_abd[a.side] = r3(a.abduction_deg);
  meta["derived"] = json{{"curve_lengths_mm", curve_lengths}, {"arm_abduction_deg_posed", arms_abd}};
  meta["deformation"] = json{{"bumps", r.bumps}};
  meta["generation_time_s"] = nullptr;
  meta["generator_version"] = kGeneratorVersion;
  meta["id"] = out.id;
  json input_lm = json::object();
  for (const auto& e : out.input_landmark_errors)
    input_lm[e.name] = json{{"error_vs_truth_mm", r3(e.error_vs_truth_mm)},
                            {"snap_distance_mm", r3(e.snap_distance_mm)},
                            {"tangential_offset_mm", r3(e.tangential_offset_mm)}};
  meta["input_landmarks"] = input_lm;
  meta["misalignment"] = misalignment_json(r);
  meta["pose"] = pose_json(options, *r.subject);
  const double s = out.scale_mm_to_file_units;
  meta["scale_mm_to_file_units"] = s;
  char frame[128];
  std::snprintf(frame, sizeof frame, "x_file = s * (R @ x_body + t), s = %g (file units per mm)", s);
  meta["scan_frame"] = frame;
  meta["scan_params"] = scan_params_json(options, r.truth->steps);
  meta["scan_stats"] = scan_stats_json(r, out);
  meta["seed"] = options.seed;
  meta["source"] = "breastfit synth: rigged template '" + model.name + "' posed with random parameters";
  meta["subject"] = subject_json(model, options);
  meta["true_params"] = params_json(model, out.true_params);
  meta["true_params"]["frame"] = "body (LPS mm); global similarity = subject scale only";
  meta["true_global_scan_mm"] = similarity_json(out.true_params_scan.global);
  meta["true_global_scan_mm"]["frame"] = "scanner frame, mm (T_body_to_scan_mm composed with the body-frame global)";
  meta["units"] = options.units;
  return meta.dump(1) + "\n";
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
  SynthCase out;
  out.id = options.case_id.empty() ? default_case_id(options) : options.case_id;
  out.units = options.units;
  out.scale_mm_to_file_units = options.units == "m" ? 1e-3 : 1.0;

  Rng rng_subject = stage_rng(options.seed, 1);
  const SubjectPose subject = sample_subject_pose(model, options, rng_subject);
  out.true_params = subject.params;
  RefinedTruth truth = refined_truth(model, subject.params, options.refinement);
  Rng rng_deform = stage_rng(options.seed, 2);
  GenerationRecord record;
  record.bumps = add_bumps(truth.mesh, options.deformation, rng_deform);
  const Points N = mesh::vertex_normals(truth.mesh);

  std::vector<Vec3> lm_body;  // truth landmarks, body frame
  for (size_t i = 0; i < truth.landmarks.size(); ++i) {
    lm_body.push_back(truth.landmarks[i].position(truth.mesh.V, truth.mesh.F));
    out.truth_landmarks_body.push_back({model.landmarks[i].name, lm_body.back()});
  }
  const std::vector<Curve> curves_body = truth_curves_body(model, truth);

  record.centre = 0.5 * (truth.mesh.V.colwise().minCoeff() + truth.mesh.V.colwise().maxCoeff()).transpose();
  const SimulatedScan sim = simulate_scan(truth.mesh, N, lm_body, record.centre, options);
  const std::vector<Vec3> input_body = input_landmarks_body(model, truth, N, lm_body, sim.body, options, out);
  const Misalignment mis = sample_misalignment(options, record.centre);
  to_scanner_frame(mis, model, sim.scan, truth.mesh, lm_body, input_body, curves_body, out);

  record.subject = &subject;
  record.truth = &truth;
  record.sim = &sim;
  record.mis = &mis;
  record.curves_body = &curves_body;
  out.meta_json = meta_json(model, options, record, out);
  return out;
}

}  // namespace breastfit::synth
