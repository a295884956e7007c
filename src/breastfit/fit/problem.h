#pragma once
/// \file The registration energy at fixed correspondences: the terms of energy_terms.h evaluated
/// at the evaluator's current parameters, with their Gauss–Newton normal equations. The problem
/// owns what the terms read (correspondences, landmarks) and re-chooses it per outer iteration.
#include <memory>
#include <optional>
#include <vector>

#include "breastfit/fit/correspondences.h"
#include "breastfit/fit/energy_term.h"
#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/fit_summary.h"
#include "breastfit/fit/landmark_target.h"
#include "breastfit/fit/normal_equations.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/model/pose_evaluator.h"

namespace breastfit::fit {

class Problem {
 public:
  /// Keeps references to model, scan and options: they must outlive the problem.
  Problem(const model::RiggedModel& model, ScanTarget& scan, const FitOptions& options,
          std::vector<LandmarkTarget> landmarks);
  ~Problem();

  model::PoseEvaluator& evaluator() { return ev_; }
  const model::PoseEvaluator& evaluator() const { return ev_; }
  const FitOptions& options() const { return options_; }
  ScanTarget& scan() { return scan_; }

  /// Recomputes correspondences at the evaluator's current pose (every `stride`-th vertex). A call
  /// with the same posed vertices and arguments as the last one keeps the pairs it found (they
  /// would be the same: e.g. the final state after the landmark predictions).
  void update_correspondences(double max_distance_mm, int stride, bool with_reverse);
  /// The warm starts of the model → scan searches (per vertex; the last face found, or −1).
  const std::vector<Index>& correspondence_hints() const { return found_.hints; }
  /// Drops all correspondences (stages that use landmarks and priors only).
  void clear_correspondences();
  /// Lets every term re-choose what it holds fixed (EnergyTerm::update) at the current pose;
  /// `robust_landmarks`: the stage down-weights landmarks beyond their tolerance.
  void update_terms(bool robust_landmarks = false);
  /// Energy at the evaluator's current parameters; with `eq`, accumulates its normal equations.
  EnergyBreakdown evaluate(NormalEquations* eq) const;
  /// The energy of one term (1/λ included) at the current parameters; with `eq`, its rows only.
  double evaluate_term(std::string_view name, NormalEquations* eq) const;

  /// The landmark terms' energy of landmark `i` alone (of the landmarks given to the problem, in
  /// their order) at the current parameters; with `eq`, its rows only.
  double evaluate_landmark(size_t i, NormalEquations* eq) const;
  const std::vector<LandmarkTarget>& landmarks() const { return landmarks_; }

  /// Flips the scan's normal sign when most of them disagree with the posed template's normals.
  void orient_scan_normals(double max_distance_mm);

  const std::vector<Correspondence>& pairs() const { return found_.pairs; }
  const std::vector<ReverseCorrespondence>& reverse_pairs() const { return found_.reverse_pairs; }
  const CorrespondenceStats& stats() const { return found_.stats; }
  const CorrespondenceStats& reverse_stats() const { return found_.reverse_stats; }

  /// What update_correspondences() chose last: the pairs both ways, their counts, the searches'
  /// warm starts and what they were found for.
  struct CorrespondenceState {
    std::vector<Correspondence> pairs;
    std::vector<ReverseCorrespondence> reverse_pairs;
    CorrespondenceStats stats, reverse_stats;
    std::vector<Index> hints, reverse_hints;  // warm starts of the closest-point searches
    struct Key {  // the posed vertices and arguments of the search (empty: none)
      Points vertices;
      double max_distance_mm = 0, normal_sign = 0;
      int stride = 0;
      bool with_reverse = false;
    };
    std::optional<Key> key;
  };
  /// The current state, to be put back with restore_correspondences() after a detour through
  /// other poses (a copy: the caller keeps it).
  const CorrespondenceState& correspondence_state() const { return found_; }
  /// Puts back a saved state: a following update_correspondences() at the pose and arguments it
  /// was found for keeps it instead of searching again (the same pairs it would find).
  void restore_correspondences(CorrespondenceState state) { found_ = std::move(state); }
  /// Mean |point-to-plane distance| over the current pairs (∞ when none).
  double kept_mae_mm() const;

 private:
  struct ActiveTerm {
    std::string name;
    double weight;  // 1/λ
    std::unique_ptr<EnergyTerm> term;
  };
  TermContext context() const;
  bool robust_landmarks_ = false;  // of the last update_terms

  const model::RiggedModel& model_;
  ScanTarget& scan_;
  const FitOptions& options_;
  std::vector<LandmarkTarget> landmarks_;
  std::vector<ActiveTerm> terms_;  // the enabled terms, in the table's order
  model::PoseEvaluator ev_;
  CorrespondenceState found_;  // its key is update_correspondences' memo
  // The posed model's index for the reverse term: built at its first search, then moved to each
  // new pose (ClosestPointIndex::move_vertices: the same answers as a new one, a fraction of the
  // cost); a cache, not part of the state.
  std::unique_ptr<spatial::ClosestPointIndex> posed_index_;
};

}  // namespace breastfit::fit
