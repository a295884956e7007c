#include "breastfit/synth/synth_options.h"

#include <cmath>
#include <sstream>

#include "breastfit/core/errors.h"

namespace breastfit::synth {
namespace {

[[noreturn]] void fail(const std::string& field, double value, const std::string& rule) {
  std::ostringstream s;
  s << "synth option " << field << " = " << value << ": " << rule;
  throw InvalidInput(s.str());
}

void check(bool ok, const std::string& field, double value, const std::string& rule) {
  if (!ok || !std::isfinite(value)) fail(field, value, rule);
}

void check_range(const Range& r, const std::string& field, double min, double max) {
  check(std::isfinite(r.lo) && r.lo >= min, field + ".lo", r.lo,
        "must be >= " + std::to_string(min));
  check(std::isfinite(r.hi) && r.hi <= max, field + ".hi", r.hi,
        "must be <= " + std::to_string(max));
  check(r.lo <= r.hi, field + ".lo", r.lo, "must not exceed hi");
}

}  // namespace

std::string_view pose_type_name(PoseType pose) { return pose == PoseType::Standing ? "standing" : "supine"; }

PoseType parse_pose_type(std::string_view text) {
  if (text == "standing") return PoseType::Standing;
  if (text == "supine") return PoseType::Supine;
  throw InvalidInput("unknown pose '" + std::string(text) + "' (expected standing or supine)");
}

void SynthOptions::validate() const {
  if (units != "mm" && units != "m") throw InvalidInput("synth option units = '" + units + "': expected mm or m");
  const auto& s = subject;
  check(s.shape_amplitude >= 0 && s.shape_amplitude <= 1, "subject.shape_amplitude", s.shape_amplitude,
        "must be in [0, 1]");
  check(s.global_scale_range >= 0 && s.global_scale_range <= 0.3, "subject.global_scale_range",
        s.global_scale_range, "must be in [0, 0.3]");
  check(s.bone_scale_range >= 0 && s.bone_scale_range <= 0.5, "subject.bone_scale_range", s.bone_scale_range,
        "must be in [0, 0.5]");
  check(s.bone_rotation_deg >= 0 && s.bone_rotation_deg <= 30, "subject.bone_rotation_deg", s.bone_rotation_deg,
        "must be in [0, 30]");
  check_range(s.standing_abduction_deg, "subject.standing_abduction_deg", 0, 120);
  check_range(s.supine_abduction_deg, "subject.supine_abduction_deg", 0, 120);
  check_range(s.standing_flexion_deg, "subject.standing_flexion_deg", -45, 45);
  check_range(s.supine_flexion_deg, "subject.supine_flexion_deg", -45, 45);
  check(s.shoulder_share >= 0 && s.shoulder_share <= 0.5, "subject.shoulder_share", s.shoulder_share,
        "must be in [0, 0.5]");
  check(s.supine_shift >= 0 && s.supine_shift <= 1, "subject.supine_shift", s.supine_shift, "must be in [0, 1]");

  const auto& d = deformation;
  check(d.n_bumps >= 0 && d.n_bumps <= 100, "deformation.n_bumps", d.n_bumps, "must be in [0, 100]");
  check_range(d.amplitude_mm, "deformation.amplitude_mm", 0, 50);
  check_range(d.width_mm, "deformation.width_mm", 1e-3, 1000);

  const auto& r = refinement;
  check(r.target_edge_mm > 0, "refinement.target_edge_mm", r.target_edge_mm, "must be > 0");
  check(r.max_steps >= 0 && r.max_steps <= 5, "refinement.max_steps", r.max_steps, "must be in [0, 5]");
  check(r.max_faces >= 1, "refinement.max_faces", r.max_faces, "must be >= 1");

  const auto& c = scanner;
  check(c.n_azimuth >= 1 && c.n_azimuth <= 360, "scanner.n_azimuth", c.n_azimuth, "must be in [1, 360]");
  check(c.arc_deg_standing >= 0 && c.arc_deg_standing <= 360, "scanner.arc_deg_standing", c.arc_deg_standing,
        "must be in [0, 360]");
  check(c.arc_deg_supine >= 0 && c.arc_deg_supine <= 180, "scanner.arc_deg_supine", c.arc_deg_supine,
        "must be in [0, 180] (the table hides the back)");
  if (c.elevations_deg.empty()) throw InvalidInput("synth option scanner.elevations_deg: needs at least one ring");
  for (double e : c.elevations_deg)
    check(e > -90 && e < 90, "scanner.elevations_deg", e, "must be in (-90, 90)");
  check(c.distance_mm > 0, "scanner.distance_mm", c.distance_mm, "must be > 0");
  check(c.fov_horizontal_deg > 0 && c.fov_horizontal_deg < 180, "scanner.fov_horizontal_deg",
        c.fov_horizontal_deg, "must be in (0, 180)");
  check(c.fov_vertical_deg > 0 && c.fov_vertical_deg < 180, "scanner.fov_vertical_deg", c.fov_vertical_deg,
        "must be in (0, 180)");
  check(c.max_incidence_deg > 0 && c.max_incidence_deg <= 90, "scanner.max_incidence_deg", c.max_incidence_deg,
        "must be in (0, 90]");
  const int n_cams = c.n_azimuth * static_cast<int>(c.elevations_deg.size());
  check(c.min_views >= 1 && c.min_views <= n_cams, "scanner.min_views", c.min_views,
        "must be in [1, number of cameras]");

  const auto& a = artifacts;
  check(a.n_holes >= 0 && a.n_holes <= 100, "artifacts.n_holes", a.n_holes, "must be in [0, 100]");
  check_range(a.hole_radius_mm, "artifacts.hole_radius_mm", 0.5, 200);
  check(a.hole_landmark_clearance_mm >= 0, "artifacts.hole_landmark_clearance_mm", a.hole_landmark_clearance_mm,
        "must be >= 0");
  check(a.min_component_faces >= 1, "artifacts.min_component_faces", a.min_component_faces, "must be >= 1");
  check(a.white_noise_mm >= 0 && a.white_noise_mm <= 20, "artifacts.white_noise_mm", a.white_noise_mm,
        "must be in [0, 20]");
  check(a.tangential_jitter_mm >= 0 && a.tangential_jitter_mm <= 20, "artifacts.tangential_jitter_mm",
        a.tangential_jitter_mm, "must be in [0, 20]");
  check(a.lowfreq_noise_mm >= 0 && a.lowfreq_noise_mm <= 20, "artifacts.lowfreq_noise_mm", a.lowfreq_noise_mm,
        "must be in [0, 20]");
  check_range(a.lowfreq_wavelength_mm, "artifacts.lowfreq_wavelength_mm", 1, 10000);
  check(a.n_fragments >= 0 && a.n_fragments <= 100, "artifacts.n_fragments", a.n_fragments, "must be in [0, 100]");
  check_range(a.fragment_distance_mm, "artifacts.fragment_distance_mm", 0, 1000);
  check_range(a.fragment_radius_mm, "artifacts.fragment_radius_mm", 1, 200);

  check(misalign_rotation_deg >= 0 && misalign_rotation_deg <= 180, "misalign_rotation_deg", misalign_rotation_deg,
        "must be in [0, 180]");
  check(misalign_translation_m >= 0 && misalign_translation_m <= 10, "misalign_translation_m",
        misalign_translation_m, "must be in [0, 10]");
  check(landmark_noise_mm >= 0 && landmark_noise_mm <= 50, "landmark_noise_mm", landmark_noise_mm,
        "must be in [0, 50]");
}

}  // namespace breastfit::synth
