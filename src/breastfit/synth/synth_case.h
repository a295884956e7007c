#pragma once
/// \file Front door of the synth layer: one synthetic scan case with full ground truth, in
/// memory (make_case) and on disk in the bench layout (write_case, case_writer.h).
///
/// Frames (as in the bench cases, docs/SYNTH.md): the subject is
/// generated in the body frame (LPS mm: x = patient left, y = posterior, z = superior); every
/// output mesh/point is in the scanner frame and the case's file units:
///   x_file = s · (R · x_body + t),  T_body_to_scan_mm = [R t; 0 1],  s = scale_mm_to_file_units.
/// Before the random rigid misalignment the scanner axes are standing X = left, Y = up,
/// Z = anterior; supine X = left, Y = anterior (up), Z = towards the feet.
///
/// Example:
/// \code
///   breastfit::synth::SynthOptions o;
///   o.seed = 7;
///   o.pose = breastfit::synth::PoseType::Supine;
///   auto c = breastfit::synth::make_case(model, o);
///   breastfit::synth::write_case("cases/synth_007_supine", c, /*force=*/false);
/// \endcode
#include <string>
#include <vector>

#include <Eigen/Core>

#include "breastfit/mesh/landmarks.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"
#include "breastfit/synth/synth_options.h"

namespace breastfit::synth {

/// Version written to meta.json ("generator_version"); bump when the output of a seed changes.
inline constexpr const char* kGeneratorVersion = "breastfit-synth 1.0";

/// Annotation error of one input landmark (truth + tangential noise, snapped to the scan).
struct InputLandmarkError {
  std::string name;
  double error_vs_truth_mm = 0;      ///< |input − truth|
  double snap_distance_mm = 0;       ///< |input − noisy position before snapping|
  double tangential_offset_mm = 0;   ///< |tangential noise|
};

/// One synthetic case. Meshes and points in the scanner frame and file units unless the name
/// says "body" (body frame, mm).
struct SynthCase {
  std::string id;                         ///< case id (meta.json "id")
  std::string units = "mm";               ///< file units: "mm" or "m"
  double scale_mm_to_file_units = 1.0;    ///< 1 (mm) or 0.001 (m)
  Eigen::Matrix4d T_body_to_scan_mm = Eigen::Matrix4d::Identity();  ///< rigid, mm

  TriangleMesh scan;                      ///< input: the simulated scan (V, F only)
  std::vector<NamedPoint> input_landmarks;  ///< input: annotated landmarks (on the scan)
  TriangleMesh truth_surface;             ///< clean posed, refined, deformed subject surface
  std::vector<NamedPoint> truth_landmarks;  ///< exact landmarks (on truth_surface)
  std::vector<Curve> truth_curves;        ///< exact drawings (~1 mm spacing, on truth_surface)

  std::vector<NamedPoint> truth_landmarks_body;  ///< exact landmarks, body frame mm
  model::PoseParams true_params;          ///< the subject's parameters, body frame (global = scale only)
  model::PoseParams true_params_scan;     ///< the same with the global similarity composed with
                                          ///< T_body_to_scan_mm (scanner frame, mm)
  std::vector<InputLandmarkError> input_landmark_errors;
  std::string meta_json;                  ///< the content of truth/meta.json
};

/// Generates a case: subject pose and shape, refinement, smooth deformation, scanner simulation,
/// defects, misalignment, annotated landmarks and the truth. Deterministic: the same model and
/// options give bit-identical results. About a second for the default template.
/// \param[in] model    rigged template (drawings named breast_contour_R/L, imf_R/L, sternum and
///                     the landmarks of kLandmarkNames are used when present; others are kept too)
/// \param[in] options  generation options
/// \throws InvalidInput for invalid options or model, or when the simulated scan is empty
SynthCase make_case(const model::RiggedModel& model, const SynthOptions& options);

/// The default case id: "synth_<seed, 3 digits>_<pose>".
std::string default_case_id(const SynthOptions& options);

}  // namespace breastfit::synth
