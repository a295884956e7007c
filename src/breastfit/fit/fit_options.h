#pragma once
/// \file Options of the registration (paper eqs. 4–9, docs/DESIGN.md §3–4) with their defaults.
///
/// Energy (all distances in mm):
///   E = 1/λD  · mean_{i∈C} ρ(r_i²)                 model vertex → scan, point-to-plane (+ μ point-to-point)
///     + 1/λR  · mean_{p∈S} ρ(r_p²)                 scan sample → model (reverse term, optional)
///     + 1/λL  · Σ_l ‖L_l(θ) − ℓ_l‖²                landmarks present in the input
///     + 1/λS  · Σ_j ‖s_j − 1‖²                     bone scales (E_S)
///     + 1/λBS · Σ_k α_k²                           blendshape weights (E_BS, squared: smooth)
///     + 1/λJ  · Σ_j ‖log(R_j R_j*ᵀ)‖² + ‖(t_j − t_j*)/τ‖²   joint regulariser (E_J), τ = joint_translation_scale_mm
///     + 1/λC  · Σ_joints ‖P_parent(c_j) − P_child(c_j)‖²      joint continuity (stiff penalty)
/// The data terms are means, so λD and λR do not depend on the template's resolution.
#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace breastfit::fit {

enum class RobustKernel { None, Huber, GemanMcClure };

/// Weights of the energy terms: E = Σ term / λ (the paper's convention: smaller λ = stronger term).
struct EnergyWeights {
  double lambda_data = 0.25;         ///< λD, mm² (mean squared point-to-plane distance)
  double lambda_reverse = 2.0;       ///< λR, mm²; ≤ 0 disables the reverse term
  double lambda_landmarks = 50.0;    ///< λL, mm² per landmark (sum over landmarks)
  double lambda_scale = 0.5;         ///< λS (dimensionless)
  double lambda_blendshapes = 10.0;  ///< λBS (dimensionless weights)
  double lambda_joints = 1.0;        ///< λJ (rad², and (mm/τ)²)
  double lambda_continuity = 0.05;   ///< λC, mm²
  double joint_translation_scale_mm = 10.0;  ///< τ in E_J
};

/// Which correspondences are kept (docs/DESIGN.md §3).
struct CorrespondenceOptions {
  double max_distance_start_mm = 40.0;  ///< distance threshold at the first iteration of a stage
  double max_distance_end_mm = 15.0;    ///< threshold reached at the end (geometric decay); 10 → 15 mm: bench true-surface 2.56 → 2.48 mm at no cost (the robust kernel already down-weights far pairs)
  double max_normal_angle_deg = 60.0;   ///< reject pairs whose normals disagree more than this
  bool reject_boundary = true;          ///< reject pairs whose closest scan feature is on an open border
  double point_to_point_weight = 0.0;   ///< μ: share of point-to-point in the data term (0 = pure point-to-plane, the paper)
  RobustKernel kernel = RobustKernel::GemanMcClure;
  double kernel_scale_mm = 5.0;         ///< σ of the robust kernel
  int reverse_samples = 800;            ///< scan samples for the reverse term
};

/// One coarse-to-fine stage: which parameter groups move and how long. The reverse term
/// (when enabled) is used in the stages that move blendshapes.
struct StageOptions {
  std::string name;
  bool global = true;        ///< similarity (rotation, translation, uniform scale)
  bool bones = false;        ///< per-bone rotation, translation, scale
  bool blendshapes = false;  ///< blendshape weights
  int max_iterations = 10;   ///< outer (correspondence) iterations
  int vertex_stride = 1;     ///< use every n-th model vertex for the data term (speed in early stages)
  bool use_data = true;      ///< false: landmarks and priors only (no correspondences)
};

/// The surface-detail layer after the parametric fit (fit/surface_detail.h; beyond the paper).
struct SurfaceDetailOptions {
  bool enabled = true;
  int passes = 2;                  ///< correspondence + solve passes
  double smoothness = 0.1;         ///< μ: weight of each edge difference relative to one correspondence
  double decay = 0.02;             ///< ε: pulls offsets without scan support to 0
  double max_distance_mm = 15.0;   ///< correspondence threshold
  double max_offset_mm = 10.0;     ///< |offset| clamp
  double kernel_scale_mm = 3.0;    ///< σ of the Geman–McClure weight on the previous pass's residual
};

struct FitOptions {
  EnergyWeights weights;
  CorrespondenceOptions correspondences;
  /// Landmarks and priors only, before any correspondence: brings the arms and breasts near the
  /// landmarks (e.g. arms abducted 90° on supine arm boards, 65° away from the template's pose),
  /// where closest points alone would latch onto the wrong surface. Skipped without landmarks.
  StageOptions landmark_pose{"landmark_pose", true, true, false, 8, 1, false};
  StageOptions rigid{"rigid", true, false, false, 8, 4};
  StageOptions pose{"pose", true, true, false, 10, 2};
  StageOptions shape{"shape", true, true, true, 10, 2};
  StageOptions refine{"refine", true, true, true, 3, 1};
  SurfaceDetailOptions detail;
  double function_tolerance = 1e-4;  ///< stop a stage when the relative energy decrease is below this
  double step_tolerance = 1e-6;      ///< stop a stage when the step's max-norm is below this
  double initial_damping = 1e-3;     ///< LM damping μ relative to diag(JᵀJ)
  int hessian_interval = 2;          ///< rebuild JᵀWJ every n-th iteration of a stage (1 = always);
                                     ///< in between only the gradient is recomputed
  int max_blendshapes = -1;          ///< use only the first n blendshapes (experiments); < 0 = all
  int max_landmarks = -1;            ///< use only the first n landmarks in the paper's order; < 0 = all
  bool use_landmarks = true;         ///< false: landmark-free fit (landmarks only reported)
  double landmark_warning_mm = 30.0; ///< warn when an input landmark is farther than this from the scan
  double max_surface_mae_mm = 8.0;   ///< a final kept-correspondence MAE above this = not converged
  double min_kept_fraction = 0.25;   ///< fewer kept correspondences than this share = not converged

  /// \throws InvalidInput naming the field, its value and the rule violated.
  void validate() const;
};

/// Reads any subset of the options from JSON (same names as the fields; weights under "weights",
/// correspondence options under "correspondences", stages under "rigid"/"pose"/"shape").
/// \throws InvalidInput for unknown keys or wrong types.
void update_from_json(FitOptions& options, const nlohmann::json& j);
/// All options as JSON (written into report.json).
nlohmann::json to_json(const FitOptions& options);

}  // namespace breastfit::fit
