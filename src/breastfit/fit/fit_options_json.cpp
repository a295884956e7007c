#include "breastfit/fit/fit_options_json.h"

#include <variant>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"

namespace breastfit::fit {
namespace {

using json = nlohmann::json;

// One table per options struct: each field's JSON key and member. Reading, writing and the list
// of known keys all come from it.
template <class S>
struct Field {
  const char* key;
  std::variant<double S::*, int S::*, bool S::*> member;
};

template <class S>
const std::vector<Field<S>>& fields();

template <>
const std::vector<Field<CorrespondenceOptions>>& fields() {
  using C = CorrespondenceOptions;
  static const std::vector<Field<C>> f = {
      {"max_distance_start_mm", &C::max_distance_start_mm}, {"max_distance_end_mm", &C::max_distance_end_mm},
      {"schedule_ramp", &C::schedule_ramp}, {"max_normal_angle_deg", &C::max_normal_angle_deg},
      {"reject_boundary", &C::reject_boundary}, {"point_to_point_weight", &C::point_to_point_weight},
      {"kernel_scale_mm", &C::kernel_scale_mm}, {"reverse_samples", &C::reverse_samples}};
  return f;
}

template <>
const std::vector<Field<StageOptions>>& fields() {
  using S = StageOptions;
  static const std::vector<Field<S>> f = {{"global", &S::global},       {"bones", &S::bones},
                                          {"blendshapes", &S::blendshapes}, {"max_iterations", &S::max_iterations},
                                          {"vertex_stride", &S::vertex_stride}, {"use_data", &S::use_data},
                                          {"robust_landmarks", &S::robust_landmarks},
                                          {"correspondence_interval", &S::correspondence_interval}};
  return f;
}

template <>
const std::vector<Field<SolverOptions>>& fields() {
  using S = SolverOptions;
  static const std::vector<Field<S>> f = {
      {"function_tolerance", &S::function_tolerance}, {"gradient_tolerance", &S::gradient_tolerance},
      {"parameter_tolerance", &S::parameter_tolerance}, {"initial_damping", &S::initial_damping},
      {"min_damping", &S::min_damping}, {"max_damping", &S::max_damping},
      {"damping_decrease", &S::damping_decrease}, {"damping_increase", &S::damping_increase},
      {"good_gain_ratio", &S::good_gain_ratio},
      {"max_step_attempts", &S::max_step_attempts}, {"min_gain_ratio", &S::min_gain_ratio},
      {"hessian_interval", &S::hessian_interval}, {"vertex_tolerance_mm", &S::vertex_tolerance_mm}};
  return f;
}

template <>
const std::vector<Field<RefitOptions>>& fields() {
  using R = RefitOptions;
  static const std::vector<Field<R>> f = {{"final_threshold", &R::final_threshold},
                                          {"max_iterations", &R::max_iterations},
                                          {"vertex_tolerance_mm", &R::vertex_tolerance_mm}};
  return f;
}

template <>
const std::vector<Field<SurfaceDetailOptions>>& fields() {
  using D = SurfaceDetailOptions;
  static const std::vector<Field<D>> f = {
      {"enabled", &D::enabled}, {"passes", &D::passes}, {"smoothness", &D::smoothness}, {"decay", &D::decay},
      {"max_distance_mm", &D::max_distance_mm}, {"max_offset_mm", &D::max_offset_mm},
      {"kernel_scale_mm", &D::kernel_scale_mm}};
  return f;
}

template <>
const std::vector<Field<FitOptions>>& fields() {
  using F = FitOptions;
  static const std::vector<Field<F>> f = {
      {"max_blendshapes", &F::max_blendshapes}, {"max_landmarks", &F::max_landmarks},
      {"use_landmarks", &F::use_landmarks}, {"landmark_warning_mm", &F::landmark_warning_mm},
      {"landmark_check_mm", &F::landmark_check_mm}, {"nipple_tip_check_mm", &F::nipple_tip_check_mm},
      {"notch_check_mm", &F::notch_check_mm}, {"nipple_below_apex_check", &F::nipple_below_apex_check},
      {"max_surface_mae_mm", &F::max_surface_mae_mm}, {"min_kept_fraction", &F::min_kept_fraction},
      {"orientation_min_margin", &F::orientation_min_margin}, {"anatomical_nipples", &F::anatomical_nipples},
      {"anatomical_nipple_apex", &F::anatomical_nipple_apex},
      {"anatomical_lowest_breast", &F::anatomical_lowest_breast}, {"anatomical_notch", &F::anatomical_notch},
      {"anatomical_shoulders", &F::anatomical_shoulders},
      {"threads", &F::threads}};
  return f;
}

void check_keys(const json& j, const std::string& path, const std::vector<std::string>& keys) {
  if (!j.is_object())
    throw InvalidInput("option " + (path.empty() ? std::string("<root>") : path) + " must be an object");
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool known = false;
    for (const auto& k : keys) known = known || it.key() == k;
    if (known) continue;
    std::string list;
    for (const auto& k : keys) list += (list.empty() ? "" : ", ") + k;
    throw InvalidInput("unknown option '" + path + it.key() + "' (expected one of: " + list + ")");
  }
}

template <typename T>
void read_value(const json& j, const std::string& key, const std::string& path, T& field) {
  auto it = j.find(key);
  if (it == j.end()) return;
  if constexpr (std::is_same_v<T, bool>) {
    if (!it->is_boolean()) throw InvalidInput("option " + path + key + " must be true or false (" + it->dump() + ")");
  } else if constexpr (std::is_integral_v<T>) {
    if (!it->is_number_integer()) throw InvalidInput("option " + path + key + " must be an integer (" + it->dump() + ")");
  } else {
    if (!it->is_number()) throw InvalidInput("option " + path + key + " must be a number (" + it->dump() + ")");
  }
  field = it->template get<T>();
}

template <class S>
std::vector<std::string> keys_of(std::initializer_list<const char*> extra = {}) {
  std::vector<std::string> keys;
  for (const auto& f : fields<S>()) keys.push_back(f.key);
  for (const char* k : extra) keys.push_back(k);
  return keys;
}

template <class S>
void read_fields(const json& j, const std::string& path, S& s) {
  for (const auto& f : fields<S>())
    std::visit([&](auto member) { read_value(j, f.key, path, s.*member); }, f.member);
}

template <class S>
json write_fields(const S& s) {
  json out = json::object();
  for (const auto& f : fields<S>()) std::visit([&](auto member) { out[f.key] = s.*member; }, f.member);
  return out;
}

RobustKernel parse_kernel(const json& value) {
  const std::string s = value.is_string() ? value.get<std::string>() : value.dump();
  for (RobustKernel k : {RobustKernel::None, RobustKernel::Huber, RobustKernel::GemanMcClure})
    if (s == to_string(k)) return k;
  throw InvalidInput("option correspondences.kernel = '" + s + "': expected none, huber or geman_mcclure");
}

void read_weights(const json& j, EnergyWeights& w) {
  std::vector<std::string> keys{"joint_translation_scale_mm"};
  for (const auto& [name, lambda] : w.lambdas()) keys.push_back("lambda_" + name);
  check_keys(j, "weights.", keys);
  for (const auto& [name, lambda] : std::vector(w.lambdas())) {
    double v = lambda;
    read_value(j, "lambda_" + name, "weights.", v);
    w.set_lambda(name, v);
  }
  read_value(j, "joint_translation_scale_mm", "weights.", w.joint_translation_scale_mm);
}

json write_weights(const EnergyWeights& w) {
  json out = json::object();
  for (const auto& [name, lambda] : w.lambdas()) out["lambda_" + name] = lambda;
  out["joint_translation_scale_mm"] = w.joint_translation_scale_mm;
  return out;
}

}  // namespace

void update_from_json(FitOptions& o, const json& j) {
  std::vector<std::string> keys = keys_of<FitOptions>();
  for (const char* k : {"weights", "correspondences", "solver", "detail", "refit"}) keys.push_back(k);
  for (const StageOptions* s : o.stages()) keys.push_back(s->name);
  if (j.is_object())
    for (const char* moved : {"function_tolerance", "step_tolerance", "initial_damping", "hessian_interval"})
      if (j.contains(moved))
        throw InvalidInput(std::string("option '") + moved + "' has moved into \"solver\" (step_tolerance is now " +
                           "solver.parameter_tolerance)");
  check_keys(j, "", keys);
  read_fields(j, "", o);
  if (auto it = j.find("weights"); it != j.end()) read_weights(*it, o.weights);
  if (auto it = j.find("correspondences"); it != j.end()) {
    check_keys(*it, "correspondences.", keys_of<CorrespondenceOptions>({"kernel"}));
    read_fields(*it, "correspondences.", o.correspondences);
    if (auto k = it->find("kernel"); k != it->end()) o.correspondences.kernel = parse_kernel(*k);
  }
  for (StageOptions* s : o.stages())
    if (auto it = j.find(s->name); it != j.end()) {
      check_keys(*it, s->name + ".", keys_of<StageOptions>());
      read_fields(*it, s->name + ".", *s);
    }
  if (auto it = j.find("solver"); it != j.end()) {
    check_keys(*it, "solver.", keys_of<SolverOptions>());
    read_fields(*it, "solver.", o.solver);
  }
  if (auto it = j.find("detail"); it != j.end()) {
    check_keys(*it, "detail.", keys_of<SurfaceDetailOptions>());
    read_fields(*it, "detail.", o.detail);
  }
  if (auto it = j.find("refit"); it != j.end()) {
    check_keys(*it, "refit.", keys_of<RefitOptions>());
    read_fields(*it, "refit.", o.refit);
  }
}

json to_json(const FitOptions& o) {
  json out = write_fields(o);
  out["weights"] = write_weights(o.weights);
  out["correspondences"] = write_fields(o.correspondences);
  out["correspondences"]["kernel"] = to_string(o.correspondences.kernel);
  for (const StageOptions* s : o.stages()) out[s->name] = write_fields(*s);
  out["solver"] = write_fields(o.solver);
  out["detail"] = write_fields(o.detail);
  out["refit"] = write_fields(o.refit);
  return out;
}

}  // namespace breastfit::fit
