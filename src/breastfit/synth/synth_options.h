#pragma once
/// \file Every knob of the synthetic scan generator (docs/SYNTH.md), with its default.
///
/// A synthetic case is a randomly posed and shaped rigged template (the "subject"), refined to
/// ~2 mm triangles and deformed slightly outside the model's space (so no fit is ever exact),
/// then seen by a simulated handheld scanner (camera ring, visibility, holes, noise, fragments,
/// table), rigidly misaligned and written in mm or m exactly like the bench cases
/// (docs/SYNTH.md "Case layout"). Lengths are millimetres unless the name says otherwise.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace breastfit::synth {

/// Patient position during the scan.
enum class PoseType { Standing, Supine };

/// "standing" / "supine".
std::string_view pose_type_name(PoseType pose);
/// Parses "standing" / "supine". \throws InvalidInput for anything else.
PoseType parse_pose_type(std::string_view text);

/// A closed interval [lo, hi] a value is drawn from (uniformly unless documented otherwise).
struct Range {
  double lo = 0.0;
  double hi = 0.0;
};

/// The subject: random shape and pose of the rigged model (body frame, LPS mm).
struct SubjectOptions {
  /// Each blendshape weight is amplitude · U(lo_k, hi_k) (bounds of the model), so 0 = the rest
  /// shape and 1 = anywhere within the bounds. In [0, 1].
  double shape_amplitude = 0.5;
  /// Global (uniform) subject scale drawn from [1 − r, 1 + r]. In [0, 0.3].
  double global_scale_range = 0.04;
  /// Each bone scale (per axis) drawn from [1 − r, 1 + r], clamped to the bone's bounds. In [0, 0.5].
  double bone_scale_range = 0.05;
  /// Random rotation of every bone that is not an arm/clavicle, up to this angle about a random
  /// axis through its pivot, degrees. In [0, 30].
  double bone_rotation_deg = 3.0;
  /// Arm abduction from the vertical (coronal plane) for a standing subject, degrees, drawn per
  /// side. Applied to bones named "upper_arm_R/L" (when the model has them); the rest abduction
  /// is read from the bone's first rest axis.
  Range standing_abduction_deg{8.0, 35.0};
  /// Arm abduction for a supine subject (arm boards), degrees.
  Range supine_abduction_deg{65.0, 95.0};
  /// Arm flexion (forward; negative = extension), degrees: standing / supine.
  Range standing_flexion_deg{-5.0, 10.0};
  Range supine_flexion_deg{-12.0, 0.0};
  /// Share of the abduction taken by the shoulder girdle (bones "clavicle_R/L"), in [0, 0.5].
  double shoulder_share = 0.25;
  /// Supine breast displacement: blendshapes whose name starts with "breast_lateral" or contains
  /// "supine" get weight U(0.6, 1)·hi·s, "breast_cranial" U(0.3, 0.7)·hi·s, and "breast_ptosis" /
  /// "breast_projection" U(0.5, 1)·lo·s (lifted, flattened), with s = this strength. In [0, 1].
  double supine_shift = 1.0;
};

/// Deformation of the truth surface outside the model's space: smooth radial-basis bumps along
/// the surface normal, exp(−d²/(2σ²)) with σ = width / 2.
struct DeformationOptions {
  int n_bumps = 4;                        ///< number of bumps, >= 0
  Range amplitude_mm{2.0, 6.0};           ///< |amplitude| (sign random), mm
  Range width_mm{60.0, 120.0};            ///< bump width (2σ), mm
};

/// Refinement of the posed model into the dense truth surface.
struct RefinementOptions {
  bool loop = true;             ///< Loop subdivision (smooth) or plain midpoint subdivision (false)
  double target_edge_mm = 2.5;  ///< subdivide until the median edge is at most this, mm (> 0)
  int max_steps = 3;            ///< at most this many subdivision steps, in [0, 5]
  int max_faces = 400000;       ///< never subdivide beyond this many triangles, >= 1
};

/// The simulated scanner (a handheld depth camera swept around the patient).
struct ScannerOptions {
  int n_azimuth = 12;                     ///< cameras per ring, >= 1
  double arc_deg_standing = 210.0;        ///< ring arc around the vertical axis, centred on the front
  double arc_deg_supine = 160.0;          ///< ring arc over the patient around the body axis
  std::vector<double> elevations_deg{-15.0, 10.0, 35.0};  ///< ring tilts towards the head, degrees
  double distance_mm = 900.0;             ///< camera distance from the torso centre, mm (> 0)
  double fov_horizontal_deg = 58.0;       ///< field of view, degrees
  double fov_vertical_deg = 45.0;
  double max_incidence_deg = 75.0;        ///< a point is seen only below this incidence angle
  int min_views = 1;                      ///< a point is kept when seen by at least this many cameras
};

/// Defects of the scan.
struct ArtifactOptions {
  int n_holes = 3;                        ///< disc holes, >= 0
  Range hole_radius_mm{8.0, 18.0};        ///< hole radius, mm
  double hole_landmark_clearance_mm = 35.0;  ///< no hole comes closer than this to a landmark
  int min_component_faces = 150;          ///< components with fewer triangles are removed
  double white_noise_mm = 0.5;            ///< sd of the per-vertex noise along the normal, mm
  double tangential_jitter_mm = 0.1;      ///< sd of the per-vertex tangential noise, mm
  double lowfreq_noise_mm = 0.5;          ///< amplitude of the smooth normal noise, mm
  Range lowfreq_wavelength_mm{60.0, 250.0};  ///< wavelengths of the smooth noise, mm
  int n_fragments = 3;                    ///< floating fragments (small patches), >= 0
  Range fragment_distance_mm{10.0, 40.0}; ///< their distance from the surface, mm
  Range fragment_radius_mm{6.0, 14.0};    ///< their radius, mm
  bool table_strip = true;                ///< supine only: strips of the table beside the torso
};

struct SynthOptions {
  std::uint64_t seed = 1;                 ///< every random draw derives from this
  PoseType pose = PoseType::Standing;     ///< standing or supine
  std::string units = "mm";               ///< units of the written files: "mm" or "m"
  std::string case_id;                    ///< id written to meta.json (default: "synth_<seed>_<pose>")
  SubjectOptions subject;
  DeformationOptions deformation;
  RefinementOptions refinement;
  ScannerOptions scanner;
  ArtifactOptions artifacts;
  double misalign_rotation_deg = 20.0;    ///< random rigid rotation up to this, about a random axis
  double misalign_translation_m = 0.3;    ///< random rigid translation up to this, metres
  double landmark_noise_mm = 2.5;         ///< sd of the tangential annotation noise per axis, mm

  /// \throws InvalidInput naming the field, its value and the rule it violates.
  void validate() const;
};

}  // namespace breastfit::synth
