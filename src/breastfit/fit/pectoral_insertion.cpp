#include "breastfit/fit/pectoral_insertion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>

#include "breastfit/fit/sliding_landmarks.h"

namespace breastfit::fit {

std::optional<Vec3> pectoral_insertion_on_scan(const Points& scan_vertices, const Vec3& fitted, const Vec3& arm_axis,
                                               const Vec3& up, const Vec3& front, const Vec3& chest,
                                               const PectoralInsertionOptions& options) {
  // The slice's frame: along the arm, forward (level with the arm), across towards the chest.
  const Vec3 along = arm_axis.normalized();
  Vec3 forward = front - front.dot(along) * along;
  if (forward.norm() < 1e-6 || !along.allFinite()) return std::nullopt;
  if (-along.dot(up.normalized()) < std::cos(options.max_abduction_deg * M_PI / 180.0)) return std::nullopt;
  forward.normalize();
  Vec3 across = along.cross(forward);
  if ((chest - fitted).dot(across) < 0) across = -across;
  const double bin = options.bin_mm;
  const int slices = static_cast<int>(std::floor((options.proximal_mm + options.distal_mm) / bin)) + 1;
  const int columns = static_cast<int>(std::floor(2 * options.across_mm / bin)) + 1;
  if (slices <= 0 || columns < 3) return std::nullopt;
  // The most anterior scan vertex in each (slice, column) cell; column 0 on the chest's side.
  const double none = -std::numeric_limits<double>::infinity();
  std::vector<double> depth(static_cast<size_t>(slices * columns), none);
  std::vector<Index> vertex(depth.size(), -1);
  for (Index i = 0; i < scan_vertices.rows(); ++i) {
    const Vec3 d = scan_vertices.row(i).transpose() - fitted;
    const double y = d.dot(forward);
    if (y < -options.max_behind_mm) continue;
    const int s = static_cast<int>(std::lround((d.dot(along) + options.proximal_mm) / bin));
    const int c = static_cast<int>(std::lround((options.across_mm - d.dot(across)) / bin));
    if (s < 0 || s >= slices || c < 0 || c >= columns) continue;
    const size_t k = static_cast<size_t>(s * columns + c);
    if (y > depth[k]) {
      depth[k] = y;
      vertex[k] = i;
    }
  }
  // From the shoulder down: the first slice with a crease between a chest side and an arm side.
  std::vector<double> chest_max(static_cast<size_t>(columns)), arm_max(static_cast<size_t>(columns));
  for (int s = 0; s < slices; ++s) {
    const double* row = depth.data() + static_cast<size_t>(s * columns);
    chest_max[0] = row[0];
    for (int c = 1; c < columns; ++c) chest_max[c] = std::max(chest_max[c - 1], row[c]);
    arm_max[columns - 1] = row[columns - 1];
    for (int c = columns - 2; c >= 0; --c) arm_max[c] = std::max(arm_max[c + 1], row[c]);
    double deepest = 0;
    int crease = -1;
    for (int c = 1; c + 1 < columns; ++c) {
      if (row[c] == none || chest_max[c - 1] == none || arm_max[c + 1] == none) continue;
      const double d = std::min(chest_max[c - 1], arm_max[c + 1]) - row[c];
      if (d > deepest) {
        deepest = d;
        crease = c;
      }
    }
    if (crease < 0 || deepest < options.min_crease_mm) continue;
    int peak = crease + 1;
    for (int c = crease + 1; c < columns; ++c)
      if (row[c] > row[peak]) peak = c;
    const Vec3 p = scan_vertices.row(vertex[static_cast<size_t>(s * columns + peak)]).transpose();
    if ((p - fitted).norm() > options.max_shift_mm) return std::nullopt;
    return p;
  }
  return std::nullopt;
}

namespace {

// The vertices the upper arm's bone of `side` mostly moves, ascending; empty without the bone.
std::vector<Index> arm_vertices(const model::RiggedModel& model, const std::string& side) {
  const auto bone = model.bone_index("upper_arm_" + side);
  return bone ? model.vertices_mostly_moved_by(*bone) : std::vector<Index>{};
}

}  // namespace

std::vector<Index> upper_arm_axis_rows(const model::RiggedModel& model, const std::string& side) {
  const auto acromion = model.landmark_index("acromion_" + side);
  std::vector<Index> rows = arm_vertices(model, side);
  if (!acromion || rows.empty()) return {};
  const Index face = model.landmarks[static_cast<size_t>(*acromion)].point.face;
  for (int k = 0; k < 3; ++k) rows.push_back(model.rest.F(face, k));
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  return rows;
}

std::optional<Vec3> upper_arm_axis(const model::RiggedModel& model, const Points& V, const model::PoseParams& params,
                                   const std::string& side) {
  const auto acromion = model.landmark_index("acromion_" + side);
  if (!acromion) return std::nullopt;
  const std::vector<Index> arm = arm_vertices(model, side);
  if (arm.size() < 10) return std::nullopt;
  Vec3 mean = Vec3::Zero();
  for (Index i : arm) mean += V.row(i).transpose();
  mean /= static_cast<double>(arm.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (Index i : arm) cov += (V.row(i).transpose() - mean) * (V.row(i).transpose() - mean).transpose();
  Vec3 axis = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(2);
  if ((mean - model_landmark_position(model, *acromion, V, params)).dot(axis) < 0) axis = -axis;
  return axis;
}

}  // namespace breastfit::fit
