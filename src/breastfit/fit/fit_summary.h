#pragma once
/// \file What a registration reports: per-iteration records, stages, energies, correspondences.
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "breastfit/fit/correspondences.h"

namespace breastfit::fit {

enum class Termination { Converged, MaxIterations, StepTooSmall, NumericalFailure, NotUsable };
const char* to_string(Termination t);

/// Energy per term at one parameter set (each already divided by its λ).
struct EnergyBreakdown {
  double data = 0, reverse = 0, landmarks = 0, scale = 0, blendshapes = 0, joints = 0, continuity = 0;
  double total() const { return data + reverse + landmarks + scale + blendshapes + joints + continuity; }
};

struct IterationRecord {
  std::string stage;
  int iteration = 0;             ///< within the stage
  double energy_before = 0;      ///< with this iteration's correspondences
  double energy_after = 0;       ///< after the accepted step (= before if none accepted)
  double max_distance_mm = 0;    ///< correspondence threshold
  int kept = 0;                  ///< kept model→scan correspondences
  double damping = 0;            ///< LM damping after the iteration
  double step_norm = 0;          ///< max-norm of the accepted step
  bool accepted = false;
};

struct StageSummary {
  std::string name;
  int iterations = 0;
  Termination termination = Termination::MaxIterations;
  double initial_energy = 0, final_energy = 0;
};

/// The surface-detail layer (fit/surface_detail.h), when applied.
struct DetailSummary {
  bool applied = false;
  int kept = 0;                          ///< scan correspondences in its last pass
  double mean_abs_mm = 0, max_abs_mm = 0;  ///< offsets along the normals
};

struct FitSummary {
  Termination termination = Termination::MaxIterations;
  std::string message;                ///< one line: why it stopped
  std::vector<StageSummary> stages;
  std::vector<IterationRecord> iterations;
  EnergyBreakdown final_energy;
  CorrespondenceStats final_correspondences;          ///< model → scan, at the end
  CorrespondenceStats final_reverse_correspondences;  ///< scan → model, at the end
  double kept_mae_mm = 0;             ///< mean |point-to-plane| over the final kept pairs
  std::string initialization;         ///< "landmarks" or "landmark-free"
  int landmarks_used = 0;
  DetailSummary detail;
  std::vector<std::string> warnings;
  double seconds = 0;                 ///< registration time (index build included)
  bool usable() const { return termination != Termination::NotUsable && termination != Termination::NumericalFailure; }
  /// One line for the terminal.
  std::string brief() const;
};

/// Called after every outer iteration (progress lines on the terminal).
using IterationCallback = std::function<void(const IterationRecord&)>;

nlohmann::json to_json(const FitSummary& s);

}  // namespace breastfit::fit
