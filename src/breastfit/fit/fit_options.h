#pragma once
/// \file Options of the registration (paper eqs. 4–9, docs/REGISTRATION.md) with their defaults.
///
/// Energy (all distances in mm), one term per entry of the table in energy_terms.h:
///   E = 1/λD  · mean_{i∈C} ρ(r_i²)                 model vertex → scan, point-to-plane (+ μ point-to-point)
///     + 1/λR  · mean_{p∈S} ρ(r_p²)                 scan sample → model (reverse term, optional)
///     + 1/λL  · Σ_l ‖L_l(θ) − ℓ_l‖²                material landmarks present in the input
///     + 1/λLS · Σ_l ‖X_l(θ) − ℓ_l‖²                sliding landmarks (lowest breast points)
///     + 1/λS  · Σ_j ‖s_j − 1‖²                     bone scales (E_S)
///     + 1/λBS · Σ_k α_k²                           blendshape weights (E_BS, squared: smooth)
///     + 1/λJ  · Σ_j ‖log(R_j R_j*ᵀ)‖² + ‖(t_j − t_j*)/τ‖²   joint regulariser (E_J), τ = joint_translation_scale_mm
///     + 1/λC  · Σ_joints ‖P_parent(c_j) − P_child(c_j)‖²      joint continuity (stiff penalty)
/// The data terms are means, so λD and λR do not depend on the template's resolution.
/// Bone scales and blendshape weights are kept within the template's bounds by projecting every
/// step onto them (model::ParamLayout::apply_increment), not by an energy term.
///
/// JSON (de)serialisation: fit_options_json.h.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace breastfit::fit {

enum class RobustKernel { None, Huber, GemanMcClure };
const char* to_string(RobustKernel k);

/// λ of every energy term by the term's name (energy_terms.h): E = Σ term / λ (the paper's
/// convention: smaller λ = stronger term). Starts at every term's default λ.
class EnergyWeights {
 public:
  EnergyWeights();
  /// λ of the term. \throws InvalidInput for a name that is not a term.
  double lambda(std::string_view term) const;
  /// \throws InvalidInput for a name that is not a term (the message lists the terms).
  void set_lambda(std::string_view term, double value);
  /// Every (term name, λ), in the table's order.
  const std::vector<std::pair<std::string, double>>& lambdas() const { return lambdas_; }

  double joint_translation_scale_mm = 10.0;  ///< τ in E_J

 private:
  std::vector<std::pair<std::string, double>> lambdas_;
};

/// Which correspondences are kept, and the schedule of the distance threshold.
struct CorrespondenceOptions {
  double max_distance_start_mm = 40.0;  ///< distance threshold at the first iteration of the first data stage
  double max_distance_end_mm = 15.0;    ///< threshold reached at the end (geometric decay); 10 → 15 mm: bench true-surface 2.56 → 2.48 mm at no cost (the robust kernel already down-weights far pairs)
  double schedule_ramp = 0.5;           ///< share of a stage's iterations over which its threshold decays to the stage's end value
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
  int max_iterations = 10;   ///< outer (correspondence) iterations: the stage's cap
  int vertex_stride = 1;     ///< use every n-th model vertex for the data term (speed in early stages)
  bool use_data = true;      ///< false: landmarks and priors only (no correspondences)
  /// Landmarks beyond their check tolerance are down-weighted (fit/landmark_check.h). Off in the
  /// first stages, where correct landmarks can still be far (arms not yet abducted).
  bool robust_landmarks = false;
  /// Re-find the correspondences (both directions) every n-th iteration of the stage (1: every
  /// iteration); in between the pairs found last are kept (their targets and normals: the
  /// point-to-plane residuals are the scan's tangent planes there) and only the model moves.
  /// 0: automatic, 2 when every landmark of the template is given, else 1 (with 3 landmarks or
  /// none the fit needs every re-association: docs/PERFORMANCE.md "Session 9").
  int correspondence_interval = 1;
};

/// The Levenberg–Marquardt loop (stage_minimizer.h, lm_strategy.h) and its convergence tests.
/// The tests apply once a stage's correspondence threshold has reached its end value.
struct SolverOptions {
  /// Converged when an accepted step lowers the energy by less than this share of it.
  double function_tolerance = 1e-4;
  /// Converged when the largest gradient entry |(JᵀWr)_i| is below this (energy per parameter unit).
  double gradient_tolerance = 1e-10;
  /// Converged when the accepted step's largest entry is below this (rad, mm, scale or weight).
  double parameter_tolerance = 1e-6;
  double initial_damping = 1e-3;   ///< LM damping μ (relative to diag(JᵀWJ)) at the start of every stage
  double min_damping = 1e-9;       ///< μ never goes below this
  double max_damping = 1e8;        ///< a step needing more damping than this counts as no decrease
  double damping_decrease = 3.0;   ///< μ ← μ / this after a good step (gain ratio ≥ good_gain_ratio)
  double damping_increase = 5.0;   ///< μ ← μ · this after a rejected step
  double good_gain_ratio = 0.0;    ///< an accepted step with a gain ratio at least this lowers μ
  int max_step_attempts = 8;       ///< damped solves tried per iteration before giving up
  /// A step is accepted when actual / predicted decrease ≥ this (0: any decrease).
  double min_gain_ratio = 0.0;
  int hessian_interval = 2;        ///< rebuild JᵀWJ every n-th iteration of a stage (1 = always);
                                   ///< in between only the gradient is recomputed
  /// Converged when an accepted step moves no model vertex farther than this, mm (0: off; the
  /// warm re-fit's RefitOptions::vertex_tolerance_mm).
  double vertex_tolerance_mm = 0.0;
};

/// The workstation's warm re-fit (fit::refit_template) after the user moved a landmark: the
/// previous fit's parameters and correspondences are nearly right, so the refine stage runs at the
/// final correspondence threshold from its first iteration and stops once its steps are small.
struct RefitOptions {
  /// The refine stage at correspondences.max_distance_end_mm from the first iteration (false:
  /// the threshold decays from max_distance_start_mm as in a stage of its own).
  bool final_threshold = true;
  /// The refine stage's cap in a re-fit: 2 of its 3 (on the 14 bench cases after a 10 mm move the
  /// re-fit lies as close to a full fit from scratch as with 3; docs/WORKSTATION.md "Speed").
  int max_iterations = 2;
  /// Stop once an accepted step moves no model vertex farther than this, mm (0: only the solver's
  /// tests).
  double vertex_tolerance_mm = 0.1;
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
  StageOptions rigid{"rigid", true, false, false, 8, 4, true, false, 0};
  StageOptions pose{"pose", true, true, false, 10, 2, true, true, 0};
  StageOptions shape{"shape", true, true, true, 10, 2, true, true, 0};
  StageOptions refine{"refine", true, true, true, 3, 1, true, true};
  SolverOptions solver;
  SurfaceDetailOptions detail;
  RefitOptions refit;
  int max_blendshapes = -1;          ///< use only the first n blendshapes (experiments); < 0 = all
  int max_landmarks = -1;            ///< use only the first n landmarks in the paper's order; < 0 = all
  bool use_landmarks = true;         ///< false: landmark-free fit (landmarks only reported)
  double landmark_warning_mm = 30.0; ///< warn when an input landmark is farther than this from the scan
  /// A given landmark farther than this from the fitted model's landmark is flagged and, in the
  /// stages with robust_landmarks, down-weighted (×2 for the mid-axillary points; landmark_check.h).
  double landmark_check_mm = 15.0;
  /// A given nipple farther than this from the breast's tip found on the scan is flagged
  /// (landmark_check.h: breast_tip_on_scan; at most 13.3 mm on 30 benchmark cases as placed).
  double nipple_tip_check_mm = 18.0;
  /// A given sternal notch farther than this sideways (1.5× that vertically) from the jugular
  /// notch found on the scan on the other landmarks' midline is flagged (midline_notch_check.h).
  double notch_check_mm = 12.0;
  /// A given nipple more than 6 mm below the breast's apex on the scan and more than 7 mm lower on
  /// its breast than the other given nipple is on its own is flagged (nipple_apex_check.h, session
  /// 24). Off for torsos whose nipples are not at their breasts' apexes by construction: the
  /// template-made synthetic ones carry the template's nipple 17–29 mm below it.
  bool nipple_below_apex_check = true;
  /// Landmark-free: the kept orientation must score this share better than the best different
  /// one (fit/orientation_search.h), else a warning says the orientation is uncertain.
  double orientation_min_margin = 0.15;
  /// Landmark-free (fewer than 3 landmarks): after the pose stage, each nipple not given is held
  /// at the breast's tip found on the scan (landmark_check.h) for the shape and refine stages.
  bool anatomical_nipples = true;
  /// With `anatomical_nipples`, for the refine stage (once the shape is fitted, and after the folds
  /// and the shoulder's landmarks are placed from the tips) each nipple is held instead at the
  /// breast's apex on the scan around the shaped model's nipple (nipple_apex.h: the tip lies 5–10 mm
  /// below the nipple). Landmark MAE 9.49 → 8.91, 9.61 → 8.46, 9.35 → 8.65 mm on 14 visible, 16
  /// validation and 10 hold-out torsos, contours within 0.1 mm (docs/REGISTRATION.md, Session 17);
  /// held from the shape stage on, or before the folds and shoulders are placed, the contours lose
  /// 0.15–0.5 mm. Only when the shape and refine stages run apart (folds or shoulders held).
  bool anatomical_nipple_apex = true;
  /// Each lowest breast point not given (landmark-free or a subset) is held, for the shape stage, at
  /// the fold found on the scan below the nipple and, for the refine stage, at the point the
  /// sternum's and the nipple's proportions give on the scan (breast_fold.h), when the detectors are
  /// sure; otherwise it is left to the fit.
  bool anatomical_lowest_breast = true;
  /// When the sternal notch is not given: it is held, from the shape stage on, where the
  /// manubrium meets the neck on the scan's midline (jugular_notch.h), when the detector is sure.
  bool anatomical_notch = true;
  /// Fewer than all the landmarks: after the shape stage the acromia, mid-axillary points (arms on boards) and pectoral
  /// insertions not given are held for the refine stage where the scan shows them (shoulder_landmarks.h: the sternum's
  /// proportions; arms hanging, the insertion at the anterior axillary fold: pectoral_insertion.h), when found. With 3 or
  /// more (but not all) landmarks given, they are placed again on the refined model and the refine stage runs once more,
  /// each refine run with twice its iterations; with the notch and nipples given and the xiphoid not, the xiphoid is held
  /// at the sternum length they predict (sternum_length.h); arms hanging, the mid-axillary points on the scan's chest
  /// wall in front of the refined model's (hanging_midaxillary.h).
  bool anatomical_shoulders = true;
  double max_surface_mae_mm = 8.0;   ///< a final kept-correspondence MAE above this = not usable
  double min_kept_fraction = 0.25;   ///< fewer kept correspondences than this share = not usable
  /// Threads for the correspondence searches and the normal equations (0: all cores, or
  /// OMP_NUM_THREADS). The results are the same bits whatever the number (fit/parallel_chunks.h).
  int threads = 0;

  /// Whether the reverse term is on (λR > 0 and scan samples to use).
  bool uses_reverse_term() const;
  /// The stages in the order they run (landmark_pose, rigid, pose, shape, refine).
  std::vector<const StageOptions*> stages() const;
  std::vector<StageOptions*> stages();

  /// \throws InvalidInput naming the field, its value and the rule violated.
  void validate() const;
};

}  // namespace breastfit::fit
