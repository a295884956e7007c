#include "breastfit/fit/fit_options.h"

#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"

namespace breastfit::fit {
namespace {

void require(bool ok, const std::string& field, double value, const std::string& rule) {
  if (!ok) {
    std::ostringstream s;
    s << "option " << field << " = " << value << ": " << rule;
    throw InvalidInput(s.str());
  }
}

const char* kernel_name(RobustKernel k) {
  switch (k) {
    case RobustKernel::None: return "none";
    case RobustKernel::Huber: return "huber";
    case RobustKernel::GemanMcClure: return "geman_mcclure";
  }
  return "none";
}

RobustKernel parse_kernel(const std::string& s) {
  if (s == "none") return RobustKernel::None;
  if (s == "huber") return RobustKernel::Huber;
  if (s == "geman_mcclure") return RobustKernel::GemanMcClure;
  throw InvalidInput("option correspondences.kernel = '" + s + "': expected none, huber or geman_mcclure");
}

// Reads j[key] into `field` when present, with a clear error on a wrong type.
template <typename T>
void read(const nlohmann::json& j, const char* key, const std::string& path, T& field) {
  auto it = j.find(key);
  if (it == j.end()) return;
  try {
    field = it->template get<T>();
  } catch (const nlohmann::json::exception&) {
    throw InvalidInput("option " + path + key + " has the wrong type (" + it->dump() + ")");
  }
}

void check_keys(const nlohmann::json& j, const std::string& path, std::initializer_list<const char*> keys) {
  if (!j.is_object()) throw InvalidInput("option " + (path.empty() ? std::string("<root>") : path) + " must be an object");
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool known = false;
    for (const char* k : keys) known = known || it.key() == k;
    if (!known) {
      std::string list;
      for (const char* k : keys) list += std::string(list.empty() ? "" : ", ") + k;
      throw InvalidInput("unknown option '" + path + it.key() + "' (expected one of: " + list + ")");
    }
  }
}

void read_stage(const nlohmann::json& j, const std::string& path, StageOptions& s) {
  check_keys(j, path, {"global", "bones", "blendshapes", "max_iterations", "vertex_stride", "use_data"});
  read(j, "global", path, s.global);
  read(j, "bones", path, s.bones);
  read(j, "blendshapes", path, s.blendshapes);
  read(j, "max_iterations", path, s.max_iterations);
  read(j, "vertex_stride", path, s.vertex_stride);
  read(j, "use_data", path, s.use_data);
}

nlohmann::json stage_json(const StageOptions& s) {
  return {{"global", s.global}, {"bones", s.bones}, {"blendshapes", s.blendshapes},
          {"max_iterations", s.max_iterations}, {"vertex_stride", s.vertex_stride}, {"use_data", s.use_data}};
}

void validate_stage(const StageOptions& s) {
  require(s.max_iterations >= 0 && s.max_iterations <= 1000, s.name + ".max_iterations", s.max_iterations,
          "must be in [0, 1000]");
  require(s.vertex_stride >= 1 && s.vertex_stride <= 64, s.name + ".vertex_stride", s.vertex_stride,
          "must be in [1, 64]");
}

}  // namespace

void FitOptions::validate() const {
  const auto& w = weights;
  auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  require(positive(w.lambda_data), "weights.lambda_data", w.lambda_data, "must be finite and > 0");
  require(std::isfinite(w.lambda_reverse), "weights.lambda_reverse", w.lambda_reverse, "must be finite (<= 0 disables)");
  require(positive(w.lambda_landmarks), "weights.lambda_landmarks", w.lambda_landmarks, "must be finite and > 0");
  require(positive(w.lambda_scale), "weights.lambda_scale", w.lambda_scale, "must be finite and > 0");
  require(positive(w.lambda_blendshapes), "weights.lambda_blendshapes", w.lambda_blendshapes, "must be finite and > 0");
  require(positive(w.lambda_joints), "weights.lambda_joints", w.lambda_joints, "must be finite and > 0");
  require(positive(w.lambda_continuity), "weights.lambda_continuity", w.lambda_continuity, "must be finite and > 0");
  require(positive(w.joint_translation_scale_mm), "weights.joint_translation_scale_mm", w.joint_translation_scale_mm,
          "must be finite and > 0");
  const auto& c = correspondences;
  require(positive(c.max_distance_start_mm), "correspondences.max_distance_start_mm", c.max_distance_start_mm, "must be > 0");
  require(positive(c.max_distance_end_mm) && c.max_distance_end_mm <= c.max_distance_start_mm,
          "correspondences.max_distance_end_mm", c.max_distance_end_mm, "must be > 0 and <= max_distance_start_mm");
  require(c.max_normal_angle_deg > 0 && c.max_normal_angle_deg <= 180, "correspondences.max_normal_angle_deg",
          c.max_normal_angle_deg, "must be in (0, 180]");
  require(c.point_to_point_weight >= 0 && c.point_to_point_weight <= 1, "correspondences.point_to_point_weight",
          c.point_to_point_weight, "must be in [0, 1]");
  require(positive(c.kernel_scale_mm), "correspondences.kernel_scale_mm", c.kernel_scale_mm, "must be > 0");
  require(c.reverse_samples >= 0 && c.reverse_samples <= 1000000, "correspondences.reverse_samples", c.reverse_samples,
          "must be in [0, 1e6]");
  validate_stage(landmark_pose);
  validate_stage(rigid);
  validate_stage(pose);
  validate_stage(shape);
  validate_stage(refine);
  const auto& d = detail;
  require(d.passes >= 0 && d.passes <= 20, "detail.passes", d.passes, "must be in [0, 20]");
  require(d.smoothness >= 0 && std::isfinite(d.smoothness), "detail.smoothness", d.smoothness, "must be finite and >= 0");
  require(positive(d.decay), "detail.decay", d.decay, "must be finite and > 0");
  require(positive(d.max_distance_mm), "detail.max_distance_mm", d.max_distance_mm, "must be finite and > 0");
  require(d.max_offset_mm >= 0 && std::isfinite(d.max_offset_mm), "detail.max_offset_mm", d.max_offset_mm,
          "must be finite and >= 0");
  require(positive(d.kernel_scale_mm), "detail.kernel_scale_mm", d.kernel_scale_mm, "must be finite and > 0");
  require(positive(function_tolerance), "function_tolerance", function_tolerance, "must be > 0");
  require(positive(step_tolerance), "step_tolerance", step_tolerance, "must be > 0");
  require(positive(initial_damping), "initial_damping", initial_damping, "must be > 0");
  require(hessian_interval >= 1 && hessian_interval <= 10, "hessian_interval", hessian_interval, "must be in [1, 10]");
  require(landmark_warning_mm > 0, "landmark_warning_mm", landmark_warning_mm, "must be > 0");
  require(positive(max_surface_mae_mm), "max_surface_mae_mm", max_surface_mae_mm, "must be > 0");
  require(min_kept_fraction >= 0 && min_kept_fraction <= 1, "min_kept_fraction", min_kept_fraction, "must be in [0, 1]");
}

void update_from_json(FitOptions& o, const nlohmann::json& j) {
  check_keys(j, "", {"weights", "correspondences", "landmark_pose", "rigid", "pose", "shape", "refine", "detail", "function_tolerance", "step_tolerance",
                     "initial_damping", "hessian_interval", "max_blendshapes", "max_landmarks", "use_landmarks", "landmark_warning_mm",
                     "max_surface_mae_mm", "min_kept_fraction"});
  if (auto it = j.find("weights"); it != j.end()) {
    const std::string p = "weights.";
    check_keys(*it, p, {"lambda_data", "lambda_reverse", "lambda_landmarks", "lambda_scale", "lambda_blendshapes",
                        "lambda_joints", "lambda_continuity", "joint_translation_scale_mm"});
    auto& w = o.weights;
    read(*it, "lambda_data", p, w.lambda_data);
    read(*it, "lambda_reverse", p, w.lambda_reverse);
    read(*it, "lambda_landmarks", p, w.lambda_landmarks);
    read(*it, "lambda_scale", p, w.lambda_scale);
    read(*it, "lambda_blendshapes", p, w.lambda_blendshapes);
    read(*it, "lambda_joints", p, w.lambda_joints);
    read(*it, "lambda_continuity", p, w.lambda_continuity);
    read(*it, "joint_translation_scale_mm", p, w.joint_translation_scale_mm);
  }
  if (auto it = j.find("correspondences"); it != j.end()) {
    const std::string p = "correspondences.";
    check_keys(*it, p, {"max_distance_start_mm", "max_distance_end_mm", "max_normal_angle_deg", "reject_boundary",
                        "point_to_point_weight", "kernel", "kernel_scale_mm", "reverse_samples"});
    auto& c = o.correspondences;
    read(*it, "max_distance_start_mm", p, c.max_distance_start_mm);
    read(*it, "max_distance_end_mm", p, c.max_distance_end_mm);
    read(*it, "max_normal_angle_deg", p, c.max_normal_angle_deg);
    read(*it, "reject_boundary", p, c.reject_boundary);
    read(*it, "point_to_point_weight", p, c.point_to_point_weight);
    std::string kernel = kernel_name(c.kernel);
    read(*it, "kernel", p, kernel);
    c.kernel = parse_kernel(kernel);
    read(*it, "kernel_scale_mm", p, c.kernel_scale_mm);
    read(*it, "reverse_samples", p, c.reverse_samples);
  }
  if (auto it = j.find("landmark_pose"); it != j.end()) read_stage(*it, "landmark_pose.", o.landmark_pose);
  if (auto it = j.find("rigid"); it != j.end()) read_stage(*it, "rigid.", o.rigid);
  if (auto it = j.find("pose"); it != j.end()) read_stage(*it, "pose.", o.pose);
  if (auto it = j.find("shape"); it != j.end()) read_stage(*it, "shape.", o.shape);
  if (auto it = j.find("refine"); it != j.end()) read_stage(*it, "refine.", o.refine);
  if (auto it = j.find("detail"); it != j.end()) {
    const std::string p = "detail.";
    check_keys(*it, p, {"enabled", "passes", "smoothness", "decay", "max_distance_mm", "max_offset_mm", "kernel_scale_mm"});
    auto& d = o.detail;
    read(*it, "enabled", p, d.enabled);
    read(*it, "passes", p, d.passes);
    read(*it, "smoothness", p, d.smoothness);
    read(*it, "decay", p, d.decay);
    read(*it, "max_distance_mm", p, d.max_distance_mm);
    read(*it, "max_offset_mm", p, d.max_offset_mm);
    read(*it, "kernel_scale_mm", p, d.kernel_scale_mm);
  }
  read(j, "function_tolerance", "", o.function_tolerance);
  read(j, "step_tolerance", "", o.step_tolerance);
  read(j, "initial_damping", "", o.initial_damping);
  read(j, "hessian_interval", "", o.hessian_interval);
  read(j, "max_blendshapes", "", o.max_blendshapes);
  read(j, "max_landmarks", "", o.max_landmarks);
  read(j, "use_landmarks", "", o.use_landmarks);
  read(j, "landmark_warning_mm", "", o.landmark_warning_mm);
  read(j, "max_surface_mae_mm", "", o.max_surface_mae_mm);
  read(j, "min_kept_fraction", "", o.min_kept_fraction);
}

nlohmann::json to_json(const FitOptions& o) {
  const auto& w = o.weights;
  const auto& c = o.correspondences;
  return {
      {"weights",
       {{"lambda_data", w.lambda_data}, {"lambda_reverse", w.lambda_reverse}, {"lambda_landmarks", w.lambda_landmarks},
        {"lambda_scale", w.lambda_scale}, {"lambda_blendshapes", w.lambda_blendshapes},
        {"lambda_joints", w.lambda_joints}, {"lambda_continuity", w.lambda_continuity},
        {"joint_translation_scale_mm", w.joint_translation_scale_mm}}},
      {"correspondences",
       {{"max_distance_start_mm", c.max_distance_start_mm}, {"max_distance_end_mm", c.max_distance_end_mm},
        {"max_normal_angle_deg", c.max_normal_angle_deg}, {"reject_boundary", c.reject_boundary},
        {"point_to_point_weight", c.point_to_point_weight}, {"kernel", kernel_name(c.kernel)},
        {"kernel_scale_mm", c.kernel_scale_mm}, {"reverse_samples", c.reverse_samples}}},
      {"landmark_pose", stage_json(o.landmark_pose)},
      {"rigid", stage_json(o.rigid)},
      {"pose", stage_json(o.pose)},
      {"shape", stage_json(o.shape)},
      {"refine", stage_json(o.refine)},
      {"detail",
       {{"enabled", o.detail.enabled}, {"passes", o.detail.passes}, {"smoothness", o.detail.smoothness},
        {"decay", o.detail.decay}, {"max_distance_mm", o.detail.max_distance_mm},
        {"max_offset_mm", o.detail.max_offset_mm}, {"kernel_scale_mm", o.detail.kernel_scale_mm}}},
      {"function_tolerance", o.function_tolerance},
      {"step_tolerance", o.step_tolerance},
      {"initial_damping", o.initial_damping},
      {"hessian_interval", o.hessian_interval},
      {"max_blendshapes", o.max_blendshapes},
      {"max_landmarks", o.max_landmarks},
      {"use_landmarks", o.use_landmarks},
      {"landmark_warning_mm", o.landmark_warning_mm},
      {"max_surface_mae_mm", o.max_surface_mae_mm},
      {"min_kept_fraction", o.min_kept_fraction},
  };
}

}  // namespace breastfit::fit
