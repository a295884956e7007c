#pragma once
/// \file Closest-point correspondences between the posed model and the scan, with rejection
/// (open border, distance, normals) and robust IRLS weights (docs/REGISTRATION.md).
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/mesh/surface_point.h"

namespace breastfit::fit {

/// Model vertex → scan.
struct Correspondence {
  Index vertex = 0;
  Vec3 target = Vec3::Zero();  ///< closest scan point, mm
  Vec3 normal = Vec3::Zero();  ///< scan normal there
  double weight = 1.0;         ///< robust IRLS weight in [0, 1]
};

/// Scan sample → model surface.
struct ReverseCorrespondence {
  Vec3 source = Vec3::Zero();  ///< scan sample, mm
  Vec3 normal = Vec3::Zero();  ///< scan normal at the sample
  SurfacePoint model_point;    ///< closest point on the posed model
  double weight = 1.0;
};

/// Counts of candidate pairs by outcome (report.json).
struct CorrespondenceStats {
  int candidates = 0;
  int kept = 0;
  int rejected_distance = 0;   ///< nothing on the scan within the threshold
  int rejected_boundary = 0;   ///< closest feature on the scan's open border
  int rejected_normal = 0;     ///< normals disagree by more than the angle limit
  double max_distance_mm = 0;  ///< the threshold used
};

/// IRLS weight of a residual r (mm) for a kernel of scale sigma (mm).
double robust_weight(RobustKernel kernel, double r, double sigma);

/// Correspondences of every `stride`-th model vertex (V, N: posed vertices and unit normals).
/// `hints` (optional, size #V, in/out): per vertex, the scan face found last time (warm start).
/// `threads`: the searches run on this many threads (≤ 0: all cores); the result does not depend on it.
std::vector<Correspondence> find_correspondences(const Points& V, const Points& N, const ScanTarget& scan,
                                                 const CorrespondenceOptions& options, double max_distance_mm,
                                                 int stride, CorrespondenceStats* stats,
                                                 std::vector<Index>* hints = nullptr, int threads = 0);

/// Closest points on the posed model (`model`: its index, built over the posed vertices or moved
/// to them with ClosestPointIndex::move_vertices) of the scan's samples; pairs whose model point
/// lies on the model's open border, beyond max_distance_mm or with disagreeing normals are
/// dropped. `hints` (optional, one per scan sample, in/out): the model face found last time.
/// `threads`: as for find_correspondences.
std::vector<ReverseCorrespondence> find_reverse_correspondences(const spatial::ClosestPointIndex& model,
                                                                const ScanTarget& scan,
                                                                const CorrespondenceOptions& options,
                                                                double max_distance_mm,
                                                                CorrespondenceStats* stats,
                                                                std::vector<Index>* hints = nullptr,
                                                                int threads = 0);

}  // namespace breastfit::fit
