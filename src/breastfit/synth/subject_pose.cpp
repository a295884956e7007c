#include "breastfit/synth/subject_pose.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace breastfit::synth {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

bool starts_with(const std::string& s, std::string_view prefix) { return s.rfind(prefix, 0) == 0; }
bool contains(const std::string& s, std::string_view part) { return s.find(part) != std::string::npos; }

Vec3 random_unit(Rng& rng) {
  for (;;) {
    const Vec3 v(rng.normal(), rng.normal(), rng.normal());
    if (v.norm() > 1e-6) return v.normalized();
  }
}

bool is_arm_bone(const std::string& name) { return starts_with(name, "upper_arm") || starts_with(name, "clavicle"); }

}  // namespace

SubjectPose sample_subject_pose(const model::RiggedModel& model, const SynthOptions& options, Rng& rng) {
  const SubjectOptions& o = options.subject;
  const bool supine = options.pose == PoseType::Supine;
  SubjectPose out;
  model::PoseParams& p = out.params;
  p = model::PoseParams::identity(model);
  p.global.scale = 1.0 + rng.uniform(-o.global_scale_range, o.global_scale_range);

  // Blendshapes: uniform within the (scaled) bounds, then the supine displacement rule.
  for (int k = 0; k < model.num_blendshapes(); ++k) {
    const auto& b = model.blendshapes[static_cast<size_t>(k)];
    p.alpha[k] = o.shape_amplitude * rng.uniform(b.lo, b.hi);
  }
  if (supine && o.supine_shift > 0) {
    for (int k = 0; k < model.num_blendshapes(); ++k) {
      const auto& b = model.blendshapes[static_cast<size_t>(k)];
      const double u = rng.uniform();
      double w = p.alpha[k];
      if (starts_with(b.name, "breast_lateral") || contains(b.name, "supine")) {
        w = (0.6 + 0.4 * u) * b.hi * o.supine_shift;
      } else if (starts_with(b.name, "breast_cranial")) {
        w = (0.3 + 0.4 * u) * b.hi * o.supine_shift;
      } else if (starts_with(b.name, "breast_ptosis") || starts_with(b.name, "breast_projection")) {
        w = (0.5 + 0.5 * u) * b.lo * o.supine_shift;
      } else {
        continue;
      }
      p.alpha[k] = std::clamp(w, b.lo, b.hi);
      out.supine_shapes.push_back(b.name);
    }
  }

  // Bones: scales for all, small rotations for the trunk, breasts and neck.
  for (int j = 0; j < model.num_bones(); ++j) {
    const auto& bone = model.bones[static_cast<size_t>(j)];
    auto& bp = p.bones[static_cast<size_t>(j)];
    for (int a = 0; a < 3; ++a)
      bp.scale[a] = std::clamp(1.0 + rng.uniform(-o.bone_scale_range, o.bone_scale_range), bone.scale_lo[a],
                               bone.scale_hi[a]);
    const Vec3 axis = random_unit(rng);
    const double angle = rng.uniform(0.0, o.bone_rotation_deg) * kDeg;
    if (!is_arm_bone(bone.name)) bp.rotation = Quat(Eigen::AngleAxisd(angle, axis));
  }

  // Arms: abduction about the antero-posterior axis through the shoulder joint, shared with the
  // clavicle, plus flexion; the arm follows the clavicle's motion of its joint point.
  for (const char* side : {"R", "L"}) {
    const auto arm = model.bone_index(std::string("upper_arm_") + side);
    if (!arm) continue;
    const auto clav = model.bone_index(std::string("clavicle_") + side);
    const auto& ab = model.bones[static_cast<size_t>(*arm)];
    const double s = ab.pivot.x() < 0 ? -1.0 : 1.0;  // patient right is -x
    Vec3 dir = ab.axes.col(0);
    if (dir.z() > 0) dir = -dir;
    ArmPose info;
    info.side = side;
    info.rest_abduction_deg = std::atan2(std::abs(dir.x()), std::max(-dir.z(), 1e-9)) / kDeg;
    const Range abd = supine ? o.supine_abduction_deg : o.standing_abduction_deg;
    const Range flex = supine ? o.supine_flexion_deg : o.standing_flexion_deg;
    info.abduction_deg = rng.uniform(abd.lo, abd.hi);
    info.flexion_deg = rng.uniform(flex.lo, flex.hi);
    const double delta = (info.abduction_deg - info.rest_abduction_deg) * kDeg;
    const Vec3 abd_axis(0.0, -s, 0.0);  // (down) x (lateral): rotates the humerus outwards
    const Quat r_abd(Eigen::AngleAxisd(delta, abd_axis));
    const Quat r_flex(Eigen::AngleAxisd(info.flexion_deg * kDeg, Vec3(-1.0, 0.0, 0.0)));
    auto& arm_pose = p.bones[static_cast<size_t>(*arm)];
    arm_pose.rotation = r_abd * r_flex;
    if (clav) {
      const auto& cb = model.bones[static_cast<size_t>(*clav)];
      const Quat r_clav(Eigen::AngleAxisd(o.shoulder_share * delta, abd_axis));
      p.bones[static_cast<size_t>(*clav)].rotation = r_clav;
      arm_pose.translation = r_clav * (ab.pivot - cb.pivot) + cb.pivot - ab.pivot;
    }
    out.arms.push_back(info);
  }
  return out;
}

}  // namespace breastfit::synth
