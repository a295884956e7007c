#include "breastfit/model/params_json.h"

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>

#include "breastfit/core/errors.h"
#include "breastfit/model/param_layout.h"

namespace breastfit::model {
namespace {

using json = nlohmann::json;

Vec3 rotation_vector(const Quat& q) {
  const Eigen::AngleAxisd aa(q.normalized());
  double angle = aa.angle();
  Vec3 axis = aa.axis();
  if (angle > std::numbers::pi) angle -= 2 * std::numbers::pi;  // shortest rotation vector
  return axis * angle;
}

Quat rotation_from_vector(const Vec3& v) {
  const double angle = v.norm();
  if (angle == 0.0) return Quat::Identity();
  return Quat(Eigen::AngleAxisd(angle, v / angle));
}

void check_sizes(const RiggedModel& model, const PoseParams& p) {
  if (static_cast<int>(p.bones.size()) != model.num_bones() || p.alpha.size() != model.num_blendshapes())
    throw InvalidInput("pose parameters have " + std::to_string(p.bones.size()) + " bones and " +
                       std::to_string(p.alpha.size()) + " blendshape weights, the model has " +
                       std::to_string(model.num_bones()) + " and " + std::to_string(model.num_blendshapes()));
}

std::string examples(const ParamLayout& layout) {
  std::vector<int> picks = {0, 3, 6};
  if (layout.num_bones() > 0) {
    picks.push_back(layout.bone_offset(0));
    picks.push_back(layout.bone_offset(0) + 3);
    picks.push_back(layout.bone_offset(layout.num_bones() - 1) + 6);
  }
  if (layout.num_blendshapes() > 0) picks.push_back(layout.blendshape_offset(0));
  std::string s;
  for (int q : picks) s += (s.empty() ? "" : ", ") + layout.name(q);
  return s + " (" + std::to_string(layout.num_params()) + " parameters; see `breastfit template info`)";
}

}  // namespace

json params_to_json(const RiggedModel& model, const PoseParams& params) {
  check_sizes(model, params);
  const ParamLayout layout(model);
  json flat = json::object();
  const Vec3 rg = rotation_vector(params.global.rotation);
  for (int c = 0; c < 3; ++c) {
    flat[layout.name(c)] = rg[c];
    flat[layout.name(3 + c)] = params.global.translation[c];
  }
  flat[layout.name(6)] = params.global.scale;
  for (int j = 0; j < model.num_bones(); ++j) {
    const int o = layout.bone_offset(j);
    const BonePose& b = params.bones[j];
    const Vec3 r = rotation_vector(b.rotation);
    for (int c = 0; c < 3; ++c) {
      flat[layout.name(o + c)] = r[c];
      flat[layout.name(o + 3 + c)] = b.translation[c];
      flat[layout.name(o + 6 + c)] = b.scale[c];
    }
  }
  for (int k = 0; k < model.num_blendshapes(); ++k) flat[layout.name(layout.blendshape_offset(k))] = params.alpha[k];
  return json{{"format", "breastfit.params"}, {"version", 1}, {"params", flat}};
}

PoseParams params_from_json(const RiggedModel& model, const json& doc) {
  return params_from_json(model, doc, PoseParams::identity(model));
}

PoseParams params_from_json(const RiggedModel& model, const json& doc, const PoseParams& base) {
  check_sizes(model, base);
  if (!doc.is_object()) throw InvalidInput("parameters must be a JSON object of name: value");
  const json* flat = &doc;
  if (doc.contains("params")) {
    flat = &doc["params"];
    if (!flat->is_object()) throw InvalidInput("parameters: 'params' must be an object of name: value");
  }
  const ParamLayout layout(model);
  std::map<std::string, int> index;
  for (int q = 0; q < layout.num_params(); ++q) index.emplace(layout.name(q), q);

  PoseParams p = base;
  // Rotation vectors, filled lazily from the base when any component is given.
  std::vector<std::optional<Vec3>> rot(1 + model.num_bones());
  auto rotation_slot = [&](int slot) -> Vec3& {
    if (!rot[slot]) rot[slot] = rotation_vector(slot == 0 ? base.global.rotation : base.bones[slot - 1].rotation);
    return *rot[slot];
  };
  for (const auto& [name, value] : flat->items()) {
    const auto it = index.find(name);
    if (it == index.end())
      throw InvalidInput("unknown parameter '" + name + "'; valid names look like " + examples(layout));
    if (!value.is_number()) throw InvalidInput("parameter '" + name + "' must be a number");
    const double v = value.get<double>();
    if (!std::isfinite(v)) throw InvalidInput("parameter '" + name + "' is not finite");
    const int q = it->second;
    switch (layout.kind(q)) {
      case ParamKind::GlobalRotation: rotation_slot(0)[q] = v; break;
      case ParamKind::GlobalTranslation: p.global.translation[q - 3] = v; break;
      case ParamKind::GlobalScale:
        if (v <= 0) throw InvalidInput("parameter 'global.scale' must be > 0, got " + std::to_string(v));
        p.global.scale = v;
        break;
      case ParamKind::BoneRotation:
      case ParamKind::BoneTranslation:
      case ParamKind::BoneScale: {
        const int j = (q - ParamLayout::kGlobalSize) / ParamLayout::kBoneSize;
        const int local = (q - ParamLayout::kGlobalSize) % ParamLayout::kBoneSize;
        if (local < 3) {
          rotation_slot(1 + j)[local] = v;
        } else if (local < 6) {
          p.bones[j].translation[local - 3] = v;
        } else {
          const int a = local - 6;
          const Bone& b = model.bones[j];
          if (v < b.scale_lo[a] || v > b.scale_hi[a])
            throw InvalidInput("parameter '" + name + "' = " + std::to_string(v) + " is outside its bounds [" +
                               std::to_string(b.scale_lo[a]) + ", " + std::to_string(b.scale_hi[a]) + "]");
          p.bones[j].scale[a] = v;
        }
        break;
      }
      case ParamKind::Blendshape: {
        const int k = q - layout.blendshape_offset(0);
        const Blendshape& s = model.blendshapes[k];
        if (v < s.lo || v > s.hi)
          throw InvalidInput("parameter '" + name + "' = " + std::to_string(v) + " is outside its bounds [" +
                             std::to_string(s.lo) + ", " + std::to_string(s.hi) + "]");
        p.alpha[k] = v;
        break;
      }
    }
  }
  if (rot[0]) p.global.rotation = rotation_from_vector(*rot[0]);
  for (int j = 0; j < model.num_bones(); ++j)
    if (rot[1 + j]) p.bones[j].rotation = rotation_from_vector(*rot[1 + j]);
  return p;
}

PoseParams read_params_json(const std::filesystem::path& path, const RiggedModel& model) {
  std::ifstream in(path);
  if (!in) throw IoError(path.string(), "cannot open the parameter file");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::exception& e) {
    throw IoError(path.string(), std::string("not valid JSON: ") + e.what());
  }
  return params_from_json(model, doc);
}

void write_params_json(const std::filesystem::path& path, const RiggedModel& model, const PoseParams& params) {
  const json doc = params_to_json(model, params);
  std::ofstream out(path);
  if (!out) throw IoError(path.string(), "cannot open for writing");
  out << doc.dump(2) << "\n";
  if (!out) throw IoError(path.string(), "write failed");
}

}  // namespace breastfit::model
