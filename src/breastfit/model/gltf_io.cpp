#include "breastfit/model/gltf_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <set>
#include <string_view>
#include <unordered_map>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/index_triangulation.h"
#include "breastfit/mesh/normals.h"

namespace breastfit::model {
namespace {

using json = nlohmann::json;
namespace tg = tinygltf;
using Mat4 = Eigen::Matrix4d;

constexpr int kMaxInfluences = 8;
constexpr double kDefaultShapeLo = 0.0;  // Blender's shape key slider range
constexpr double kDefaultShapeHi = 1.0;
constexpr int kFormatVersion = 1;

// ---------------------------------------------------------------------------------------------
// Frames: glTF (metres, +Y up, facing +Z) <-> model (mm, LPS).

Vec3 gltf_to_model(const Vec3& p) { return 1000.0 * Vec3(p.x(), -p.z(), p.y()); }
Vec3 model_to_gltf(const Vec3& p) { return Vec3(p.x(), p.z(), -p.y()) / 1000.0; }

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// ---------------------------------------------------------------------------------------------
// tinygltf::Value <-> nlohmann::json

json to_json(const tg::Value& v) {
  switch (v.Type()) {
    case tg::BOOL_TYPE: return v.Get<bool>();
    case tg::INT_TYPE: return v.Get<int>();
    case tg::REAL_TYPE: return v.Get<double>();
    case tg::STRING_TYPE: return v.Get<std::string>();
    case tg::ARRAY_TYPE: {
      json a = json::array();
      for (size_t i = 0; i < v.ArrayLen(); ++i) a.push_back(to_json(v.Get(static_cast<int>(i))));
      return a;
    }
    case tg::OBJECT_TYPE: {
      json o = json::object();
      for (const auto& key : v.Keys()) o[key] = to_json(v.Get(key));
      return o;
    }
    default: return nullptr;
  }
}

tg::Value to_value(const json& j) {
  switch (j.type()) {
    case json::value_t::boolean: return tg::Value(j.get<bool>());
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return tg::Value(static_cast<int>(j.get<long long>()));
    case json::value_t::number_float: return tg::Value(j.get<double>());
    case json::value_t::string: return tg::Value(j.get<std::string>());
    case json::value_t::array: {
      tg::Value::Array a;
      for (const auto& e : j) a.push_back(to_value(e));
      return tg::Value(std::move(a));
    }
    case json::value_t::object: {
      tg::Value::Object o;
      for (const auto& [k, e] : j.items()) o[k] = to_value(e);
      return tg::Value(std::move(o));
    }
    default: return tg::Value();
  }
}

json vec_json(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

// =============================================================================================
// Loading

/// One vertex's skin influences (joint index within the skin, weight).
using Influences = std::vector<std::pair<int, double>>;

/// The triangle primitives of the mesh, concatenated in order, as stored (glTF frame).
struct RawMesh {
  std::vector<Vec3> positions;
  std::vector<Eigen::Vector3i> faces;
  std::vector<Influences> influences;     // per vertex
  std::vector<std::vector<Vec3>> morphs;  // [target][vertex]
  int num_targets = -1;                   // -1 until the first primitive is read
};

/// The bones in model order (parents first) and the skin's bind state.
struct Skeleton {
  std::vector<int> bone_joint;    // bone -> joint index in skin
  std::vector<int> joint_bone;    // joint index -> bone
  std::vector<int> bone_parent;   // bone -> parent bone or -1
  std::vector<Mat4> skin_matrix;  // per joint: world_j · IBM_j
  bool bind_is_identity = true;
};

/// Rest positions (model frame) and morph displacements of every raw vertex.
struct ModelFrameVertices {
  Points V;
  std::vector<std::vector<Vec3>> disp;  // [target][vertex]
};

/// Raw vertex -> kept vertex: remap[i] is the raw vertex i is welded to (itself when kept),
/// compact[i] the index of a kept raw vertex in the model (-1 for welded ones).
struct Welding {
  std::vector<Index> remap;
  std::vector<Index> compact;
  Index kept = 0;
};

class Loader {
 public:
  Loader(std::string path, const tg::Model& g, std::string mesh)
      : path_(std::move(path)), g_(g), wanted_mesh_(std::move(mesh)) {}
  RiggedModel run();

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw IoError(path_, problem); }

  struct AccessorData {
    size_t count = 0;
    int components = 0;
    std::vector<double> values;  // count × components
    double at(size_t i, int c) const { return values[i * components + c]; }
  };
  AccessorData read_accessor(int index, int expected_type, const std::string& what) const;
  Mat4 local_matrix(const tg::Node& n) const;
  void compute_world_matrices();
  Vec3 json_vec3(const json& j, const std::string& what) const;

  // The steps of run(), in order.
  void select_mesh_node();
  void read_breastfit_extras();
  RawMesh read_primitives() const;
  void read_primitive(size_t pi, RawMesh& raw) const;
  void read_faces(const tg::Primitive& prim, const std::string& pw, size_t base, size_t n, RawMesh& raw) const;
  void read_skin_attributes(const tg::Primitive& prim, const std::string& pw, size_t base, size_t n,
                            RawMesh& raw) const;
  void read_morph_targets(const tg::Primitive& prim, const std::string& pw, size_t base, size_t n,
                          RawMesh& raw) const;
  Skeleton read_skeleton(std::vector<Influences>& influences) const;
  void order_bones(Skeleton& sk) const;
  void compute_skin_matrices(Skeleton& sk) const;
  ModelFrameVertices to_model_frame(const RawMesh& raw, const Skeleton& sk) const;
  Welding weld(const RawMesh& raw) const;
  std::string model_name() const;
  void add_bones(const Skeleton& sk, RiggedModel& model) const;
  Bone joint_bone(int joint) const;
  void add_weights(const RawMesh& raw, const Skeleton& sk, const Welding& w, RiggedModel& model) const;
  void add_blendshapes(const ModelFrameVertices& mv, const Welding& w, RiggedModel& model) const;
  void add_annotations(RiggedModel& model) const;
  SurfacePoint surface_point(const json& face, const json& bary, const std::string& what) const;
  json extras_array(const char* key) const;
  std::string item_name(const json& item, const std::string& what) const;

  std::string path_;
  const tg::Model& g_;
  std::vector<int> parent_;
  std::vector<Mat4> world_;
  // Set by select_mesh_node() and read_breastfit_extras().
  int mesh_node_ = -1;
  const tg::Mesh* mesh_ = nullptr;
  const tg::Skin* skin_ = nullptr;
  std::string wanted_mesh_;  // the skinned mesh asked for by name (empty: the only one)
  json mesh_extras_;
  const json* bf_ = nullptr;  // mesh_extras_["breastfit"], or null
};

double read_component(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      uint8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      int32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: {
      double v;
      std::memcpy(&v, p, 8);
      return v;
    }
    default: return 0.0;
  }
}

const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "?";
  }
}

Loader::AccessorData Loader::read_accessor(int index, int expected_type, const std::string& what) const {
  if (index < 0 || index >= static_cast<int>(g_.accessors.size()))
    fail(what + ": accessor " + std::to_string(index) + " does not exist");
  const tg::Accessor& a = g_.accessors[index];
  const std::string who = what + " (accessor " + std::to_string(index) + ")";
  if (a.type != expected_type) fail(who + ": expected type " + type_name(expected_type));
  const int comp_size = tg::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
  const int ncomp = tg::GetNumComponentsInType(static_cast<uint32_t>(a.type));
  if (comp_size <= 0 || ncomp <= 0) fail(who + ": unsupported component type");
  AccessorData d;
  d.count = a.count;
  d.components = ncomp;
  d.values.assign(a.count * ncomp, 0.0);

  // Reads `count` elements starting at byte `offset` of buffer view `view` with component type `ct`.
  auto view_bytes = [&](int view, size_t offset, size_t count, size_t elem_size, bool use_view_stride,
                        const std::string& part) -> std::pair<const unsigned char*, size_t> {
    if (view < 0 || view >= static_cast<int>(g_.bufferViews.size()))
      fail(who + ": " + part + " buffer view " + std::to_string(view) + " does not exist");
    const tg::BufferView& bv = g_.bufferViews[view];
    const size_t stride_or_zero = use_view_stride ? bv.byteStride : 0;
    if (bv.buffer < 0 || bv.buffer >= static_cast<int>(g_.buffers.size()))
      fail(who + ": buffer " + std::to_string(bv.buffer) + " does not exist");
    const tg::Buffer& buf = g_.buffers[bv.buffer];
    const size_t stride = stride_or_zero ? stride_or_zero : elem_size;
    if (bv.byteOffset + bv.byteLength > buf.data.size()) fail(who + ": buffer view exceeds its buffer");
    if (count > 0 && offset + stride * (count - 1) + elem_size > bv.byteLength)
      fail(who + ": " + part + " data exceeds its buffer view");
    return {buf.data.data() + bv.byteOffset + offset, stride};
  };

  const size_t elem_size = static_cast<size_t>(comp_size) * ncomp;
  if (a.bufferView >= 0) {
    auto [base, step] = view_bytes(a.bufferView, a.byteOffset, a.count, elem_size, true, "data");
    for (size_t i = 0; i < a.count; ++i)
      for (int c = 0; c < ncomp; ++c)
        d.values[i * ncomp + c] = read_component(base + i * step + c * comp_size, a.componentType, a.normalized);
  }
  if (a.sparse.isSparse) {
    const size_t n = static_cast<size_t>(std::max(a.sparse.count, 0));
    const int ict = a.sparse.indices.componentType;
    const int isize = tg::GetComponentSizeInBytes(static_cast<uint32_t>(ict));
    if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(who + ": sparse indices must be unsigned integers");
    auto [ibase, istep] =
        view_bytes(a.sparse.indices.bufferView, a.sparse.indices.byteOffset, n, isize, false, "sparse indices");
    auto [vbase, vstep] = view_bytes(a.sparse.values.bufferView, a.sparse.values.byteOffset, n, elem_size, false,
                                     "sparse values");
    for (size_t s = 0; s < n; ++s) {
      const double idx = read_component(ibase + s * istep, ict, false);
      if (idx < 0 || idx >= static_cast<double>(a.count)) fail(who + ": sparse index out of range");
      const size_t i = static_cast<size_t>(idx);
      for (int c = 0; c < ncomp; ++c)
        d.values[i * ncomp + c] = read_component(vbase + s * vstep + c * comp_size, a.componentType, a.normalized);
    }
  }
  for (double v : d.values)
    if (!std::isfinite(v)) fail(who + ": non-finite value");
  return d;
}

Mat4 Loader::local_matrix(const tg::Node& n) const {
  Mat4 M = Mat4::Identity();
  if (n.matrix.size() == 16) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) M(r, c) = n.matrix[4 * c + r];
    return M;
  }
  Mat3 L = Mat3::Identity();
  if (n.rotation.size() == 4)
    L = Quat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]).normalized().toRotationMatrix();
  if (n.scale.size() == 3) L = L * Vec3(n.scale[0], n.scale[1], n.scale[2]).asDiagonal();
  M.topLeftCorner<3, 3>() = L;
  if (n.translation.size() == 3) M.topRightCorner<3, 1>() = Vec3(n.translation[0], n.translation[1], n.translation[2]);
  return M;
}

void Loader::compute_world_matrices() {
  const int nn = static_cast<int>(g_.nodes.size());
  parent_.assign(nn, -1);
  for (int i = 0; i < nn; ++i) {
    for (int c : g_.nodes[i].children) {
      if (c < 0 || c >= nn) fail("node " + std::to_string(i) + " has a child index out of range");
      if (parent_[c] != -1) fail("node " + std::to_string(c) + " has two parents");
      parent_[c] = i;
    }
  }
  world_.assign(nn, Mat4::Identity());
  std::vector<int> state(nn, 0);  // 0 = todo, 1 = in progress, 2 = done
  std::function<void(int)> visit = [&](int i) {
    if (state[i] == 2) return;
    if (state[i] == 1) fail("the node hierarchy has a cycle at node " + std::to_string(i));
    state[i] = 1;
    Mat4 parent_world = Mat4::Identity();
    if (parent_[i] >= 0) {
      visit(parent_[i]);
      parent_world = world_[parent_[i]];
    }
    world_[i] = parent_world * local_matrix(g_.nodes[i]);
    state[i] = 2;
  };
  for (int i = 0; i < nn; ++i) visit(i);
}

Vec3 Loader::json_vec3(const json& j, const std::string& what) const {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    fail(what + " must be an array of 3 numbers");
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

RiggedModel Loader::run() {
  compute_world_matrices();
  select_mesh_node();
  read_breastfit_extras();
  RawMesh raw = read_primitives();
  const Skeleton sk = read_skeleton(raw.influences);
  const ModelFrameVertices mv = to_model_frame(raw, sk);
  const Welding w = weld(raw);

  RiggedModel model;
  model.rest.V.resize(w.kept, 3);
  for (size_t i = 0; i < raw.positions.size(); ++i)
    if (w.compact[i] >= 0) model.rest.V.row(w.compact[i]) = mv.V.row(static_cast<Index>(i));
  model.rest.F.resize(static_cast<Index>(raw.faces.size()), 3);
  for (size_t f = 0; f < raw.faces.size(); ++f)
    for (int c = 0; c < 3; ++c) model.rest.F(static_cast<Index>(f), c) = w.compact[w.remap[raw.faces[f][c]]];
  model.name = model_name();
  add_bones(sk, model);
  add_weights(raw, sk, w, model);
  add_blendshapes(mv, w, model);
  if (bf_) add_annotations(model);

  try {
    model.validate();
  } catch (const InvalidInput& e) {
    fail(e.what());
  }
  return model;
}

/// The mesh node: first with mesh and skin, else first with a mesh; its mesh and skin checked.
void Loader::select_mesh_node() {
  std::vector<int> skinned;
  std::string names;
  const auto name_of = [&](int i) {
    const tg::Node& n = g_.nodes[i];
    if (!n.name.empty()) return n.name;
    if (n.mesh < static_cast<int>(g_.meshes.size()) && !g_.meshes[n.mesh].name.empty()) return g_.meshes[n.mesh].name;
    return "node " + std::to_string(i);
  };
  for (size_t i = 0; i < g_.nodes.size(); ++i)
    if (g_.nodes[i].mesh >= 0 && g_.nodes[i].skin >= 0) {
      skinned.push_back(static_cast<int>(i));
      names += std::string(names.empty() ? "" : ", ") + "'" + name_of(static_cast<int>(i)) + "'";
    }
  if (!wanted_mesh_.empty()) {
    for (int i : skinned) {
      const tg::Node& n = g_.nodes[i];
      const bool mesh_named = n.mesh < static_cast<int>(g_.meshes.size()) && g_.meshes[n.mesh].name == wanted_mesh_;
      if (n.name == wanted_mesh_ || mesh_named) mesh_node_ = i;
    }
    if (mesh_node_ < 0)
      fail("no skinned mesh named '" + wanted_mesh_ + "' (" +
           (skinned.empty() ? std::string("the file has none") : "the file has " + names) + ")");
  } else if (skinned.size() > 1) {
    fail(std::to_string(skinned.size()) + " skinned meshes (" + names + "): choose one with --mesh NAME");
  } else if (skinned.size() == 1) {
    mesh_node_ = skinned.front();
  }
  for (size_t i = 0; i < g_.nodes.size() && mesh_node_ < 0; ++i)
    if (g_.nodes[i].mesh >= 0) mesh_node_ = static_cast<int>(i);
  if (mesh_node_ < 0) fail("no node with a mesh");
  const tg::Node& node = g_.nodes[mesh_node_];
  if (node.mesh >= static_cast<int>(g_.meshes.size())) fail("mesh index out of range");
  mesh_ = &g_.meshes[node.mesh];
  if (node.skin >= 0) {
    if (node.skin >= static_cast<int>(g_.skins.size())) fail("skin index out of range");
    skin_ = &g_.skins[node.skin];
    if (skin_->joints.empty()) fail("the skin has no joints");
    for (int jn : skin_->joints)
      if (jn < 0 || jn >= static_cast<int>(g_.nodes.size())) fail("skin joint index out of range");
  }
}

/// mesh.extras, and its "breastfit" object (a file written by save_gltf) with a supported version.
void Loader::read_breastfit_extras() {
  mesh_extras_ = to_json(mesh_->extras);
  if (mesh_extras_.is_object() && mesh_extras_.contains("breastfit")) {
    bf_ = &mesh_extras_["breastfit"];
    if (!bf_->is_object()) fail("mesh.extras.breastfit must be an object");
    if (bf_->contains("version") &&
        (!(*bf_)["version"].is_number_integer() || (*bf_)["version"].get<int>() > kFormatVersion))
      fail("mesh.extras.breastfit.version is not supported by this breastfit (max " + std::to_string(kFormatVersion) +
           ")");
  }
}

/// All triangle primitives, concatenated.
RawMesh Loader::read_primitives() const {
  RawMesh raw;
  for (size_t pi = 0; pi < mesh_->primitives.size(); ++pi) read_primitive(pi, raw);
  if (raw.faces.empty()) fail("the mesh has no triangles");
  if (raw.num_targets < 0) raw.num_targets = 0;
  return raw;
}

void Loader::read_primitive(size_t pi, RawMesh& raw) const {
  const tg::Primitive& prim = mesh_->primitives[pi];
  if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      prim.mode != TINYGLTF_MODE_TRIANGLE_FAN)
    return;
  const std::string pw = "primitive " + std::to_string(pi);
  const auto pos_it = prim.attributes.find("POSITION");
  if (pos_it == prim.attributes.end()) fail(pw + " has no POSITION attribute");
  const AccessorData pos = read_accessor(pos_it->second, TINYGLTF_TYPE_VEC3, pw + " POSITION");
  const size_t n = pos.count;
  const size_t base = raw.positions.size();
  for (size_t i = 0; i < n; ++i) raw.positions.emplace_back(pos.at(i, 0), pos.at(i, 1), pos.at(i, 2));
  read_faces(prim, pw, base, n, raw);
  raw.influences.resize(base + n);
  if (skin_) read_skin_attributes(prim, pw, base, n, raw);
  read_morph_targets(prim, pw, base, n, raw);
}

/// The primitive's triangles (indexed or not), offset by `base`, the primitive's first vertex. Mode 4 lists
/// triangles; strips (mode 5) and fans (mode 6) are triangulated, skipping triangles that repeat a vertex.
void Loader::read_faces(const tg::Primitive& prim, const std::string& pw, size_t base, size_t n,
                        RawMesh& raw) const {
  std::vector<Index> order;  // the vertex sequence, primitive-local
  if (prim.indices >= 0) {
    const AccessorData idx = read_accessor(prim.indices, TINYGLTF_TYPE_SCALAR, pw + " indices");
    order.reserve(idx.count);
    for (size_t k = 0; k < idx.count; ++k) {
      const double v = idx.values[k];
      if (v < 0 || v >= static_cast<double>(n) || v != std::floor(v))
        fail(pw + ": index " + std::to_string(static_cast<long long>(v)) + " out of range [0, " + std::to_string(n) +
             ")");
      order.push_back(static_cast<Index>(v));
    }
  } else {
    for (size_t k = 0; k < n; ++k) order.push_back(static_cast<Index>(k));
  }
  std::vector<Index> tris;
  if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    mesh::append_strip_triangles(order.data(), order.size(), tris);
  } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    mesh::append_fan_triangles(order.data(), order.size(), tris);
  } else if (order.size() % 3 != 0) {
    fail(pw + (prim.indices >= 0 ? ": index count " + std::to_string(order.size()) + " is not a multiple of 3"
                                 : std::string(": non-indexed vertex count is not a multiple of 3")));
  } else {
    tris = std::move(order);
  }
  for (size_t t = 0; t < tris.size() / 3; ++t)
    raw.faces.emplace_back(static_cast<int>(base) + tris[3 * t], static_cast<int>(base) + tris[3 * t + 1],
                           static_cast<int>(base) + tris[3 * t + 2]);
}

/// JOINTS_k / WEIGHTS_k (k < 2) of the primitive: the non-zero influences of its vertices.
void Loader::read_skin_attributes(const tg::Primitive& prim, const std::string& pw, size_t base, size_t n,
                                  RawMesh& raw) const {
  for (int set = 0; set < kMaxInfluences / 4; ++set) {
    const auto jit = prim.attributes.find("JOINTS_" + std::to_string(set));
    const auto wit = prim.attributes.find("WEIGHTS_" + std::to_string(set));
    if (jit == prim.attributes.end() && wit == prim.attributes.end()) continue;
    if (jit == prim.attributes.end() || wit == prim.attributes.end())
      fail(pw + ": JOINTS_" + std::to_string(set) + " and WEIGHTS_" + std::to_string(set) + " must come together");
    const AccessorData J = read_accessor(jit->second, TINYGLTF_TYPE_VEC4, pw + " JOINTS_" + std::to_string(set));
    const AccessorData W = read_accessor(wit->second, TINYGLTF_TYPE_VEC4, pw + " WEIGHTS_" + std::to_string(set));
    if (J.count != n || W.count != n) fail(pw + ": skin attribute count differs from POSITION count");
    for (size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 4; ++c) {
        const double w = W.at(i, c);
        if (w < 0) fail(pw + ": negative skin weight at vertex " + std::to_string(i));
        if (w == 0) continue;
        const double j = J.at(i, c);
        if (j < 0 || j >= static_cast<double>(skin_->joints.size()))
          fail(pw + ": joint index " + std::to_string(static_cast<long long>(j)) + " out of range");
        raw.influences[base + i].emplace_back(static_cast<int>(j), w);
      }
    }
  }
}

/// The primitive's morph target POSITION displacements (every primitive has as many targets as
/// the first one).
void Loader::read_morph_targets(const tg::Primitive& prim, const std::string& pw, size_t base, size_t n,
                                RawMesh& raw) const {
  const int nt = static_cast<int>(prim.targets.size());
  if (raw.num_targets < 0) {
    raw.num_targets = nt;
    raw.morphs.assign(nt, {});
  } else if (nt != raw.num_targets) {
    fail(pw + " has " + std::to_string(nt) + " morph targets, the first primitive " + std::to_string(raw.num_targets));
  }
  for (int k = 0; k < nt; ++k) {
    raw.morphs[k].resize(base + n, Vec3::Zero());
    const auto it = prim.targets[k].find("POSITION");
    if (it == prim.targets[k].end()) continue;
    const AccessorData D =
        read_accessor(it->second, TINYGLTF_TYPE_VEC3, pw + " morph target " + std::to_string(k) + " POSITION");
    if (D.count != n) fail(pw + ": morph target " + std::to_string(k) + " count differs from POSITION count");
    for (size_t i = 0; i < n; ++i) raw.morphs[k][base + i] = Vec3(D.at(i, 0), D.at(i, 1), D.at(i, 2));
  }
}

/// The bones and bind matrices of the skin, and the influences merged per joint and normalised
/// (unweighted vertices go to the first root bone). Without a skin: one root bone at the mesh
/// node, every vertex bound to it.
Skeleton Loader::read_skeleton(std::vector<Influences>& influences) const {
  Skeleton sk;
  if (!skin_) {
    sk.bone_joint = {0};
    sk.joint_bone = {0};
    sk.bone_parent = {-1};
    for (auto& inf : influences) inf = {{0, 1.0}};
    sk.skin_matrix = {world_[mesh_node_]};
    sk.bind_is_identity = (world_[mesh_node_] - Mat4::Identity()).cwiseAbs().maxCoeff() <= 1e-12;
    return sk;
  }
  order_bones(sk);
  compute_skin_matrices(sk);
  for (auto& inf : influences) {
    std::map<int, double> merged;
    for (const auto& [j, w] : inf) merged[j] += w;
    inf.assign(merged.begin(), merged.end());
    double sum = 0;
    for (const auto& [j, w] : inf) sum += w;
    if (sum <= 0) {
      inf = {{sk.bone_joint[0], 1.0}};
      continue;
    }
    for (auto& [j, w] : inf) w /= sum;
  }
  return sk;
}

/// Bones from the skin's joints: parents (the nearest ancestor node that is a joint) first,
/// otherwise in skin order.
void Loader::order_bones(Skeleton& sk) const {
  const int nj = static_cast<int>(skin_->joints.size());
  std::map<int, int> node_joint;
  for (int j = 0; j < nj; ++j)
    if (!node_joint.emplace(skin_->joints[j], j).second) fail("the skin lists a joint node twice");
  std::vector<int> joint_parent(nj, -1);
  for (int j = 0; j < nj; ++j) {
    for (int a = parent_[skin_->joints[j]]; a >= 0; a = parent_[a]) {
      const auto it = node_joint.find(a);
      if (it != node_joint.end()) {
        joint_parent[j] = it->second;
        break;
      }
    }
  }
  sk.joint_bone.assign(nj, -1);
  while (static_cast<int>(sk.bone_joint.size()) < nj) {
    for (int j = 0; j < nj; ++j) {
      if (sk.joint_bone[j] >= 0) continue;
      if (joint_parent[j] >= 0 && sk.joint_bone[joint_parent[j]] < 0) continue;
      sk.joint_bone[j] = static_cast<int>(sk.bone_joint.size());
      sk.bone_joint.push_back(j);
      sk.bone_parent.push_back(joint_parent[j] >= 0 ? sk.joint_bone[joint_parent[j]] : -1);
      break;
    }
  }
}

/// world_j · IBM_j per joint, and whether they are all the identity (the file's vertices are
/// then already in the bind pose).
void Loader::compute_skin_matrices(Skeleton& sk) const {
  const int nj = static_cast<int>(skin_->joints.size());
  std::vector<Mat4> ibm(nj, Mat4::Identity());
  if (skin_->inverseBindMatrices >= 0) {
    const AccessorData M = read_accessor(skin_->inverseBindMatrices, TINYGLTF_TYPE_MAT4, "inverseBindMatrices");
    if (static_cast<int>(M.count) < nj) fail("inverseBindMatrices has fewer matrices than joints");
    for (int j = 0; j < nj; ++j)
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) ibm[j](r, c) = M.at(j, 4 * c + r);
  }
  sk.skin_matrix.resize(nj);
  for (int j = 0; j < nj; ++j) {
    sk.skin_matrix[j] = world_[skin_->joints[j]] * ibm[j];
    if ((sk.skin_matrix[j] - Mat4::Identity()).cwiseAbs().maxCoeff() > 1e-5) sk.bind_is_identity = false;
  }
}

/// Rest positions and displacements in the model frame (skinned to the bind pose when the
/// bind matrices are not the identity).
ModelFrameVertices Loader::to_model_frame(const RawMesh& raw, const Skeleton& sk) const {
  const size_t nv = raw.positions.size();
  ModelFrameVertices mv;
  mv.V.resize(static_cast<Index>(nv), 3);
  mv.disp.assign(raw.num_targets, std::vector<Vec3>(nv));
  for (size_t i = 0; i < nv; ++i) {
    Vec3 p = raw.positions[i];
    Mat3 lin = Mat3::Identity();
    if (!sk.bind_is_identity) {
      Mat4 S = Mat4::Zero();
      for (const auto& [j, w] : raw.influences[i]) S += w * sk.skin_matrix[j];
      p = S.topLeftCorner<3, 3>() * p + S.topRightCorner<3, 1>();
      lin = S.topLeftCorner<3, 3>();
    }
    mv.V.row(static_cast<Index>(i)) = gltf_to_model(p).transpose();
    for (int k = 0; k < raw.num_targets; ++k) mv.disp[k][i] = gltf_to_model(lin * raw.morphs[k][i]);
  }
  return mv;
}

/// Welds bit-identical duplicates (same float position, influences and morph displacements) of
/// foreign files; files with breastfit extras keep every vertex.
Welding Loader::weld(const RawMesh& raw) const {
  const size_t nv = raw.positions.size();
  Welding w;
  w.remap.resize(nv);
  for (size_t i = 0; i < nv; ++i) w.remap[i] = static_cast<Index>(i);
  if (!bf_) {
    struct Key {
      float x, y, z;
      bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
    };
    struct KeyHash {
      size_t operator()(const Key& k) const {
        uint32_t a, b, c;
        std::memcpy(&a, &k.x, 4);
        std::memcpy(&b, &k.y, 4);
        std::memcpy(&c, &k.z, 4);
        return (static_cast<size_t>(a) * 73856093u) ^ (static_cast<size_t>(b) * 19349663u) ^
               (static_cast<size_t>(c) * 83492791u);
      }
    };
    std::unordered_map<Key, std::vector<size_t>, KeyHash> buckets;
    for (size_t i = 0; i < nv; ++i) {
      const Key key{static_cast<float>(raw.positions[i].x()), static_cast<float>(raw.positions[i].y()),
                    static_cast<float>(raw.positions[i].z())};
      auto& list = buckets[key];
      bool merged = false;
      for (size_t r : list) {
        bool same = raw.influences[r] == raw.influences[i];
        for (int k = 0; same && k < raw.num_targets; ++k) same = raw.morphs[k][r] == raw.morphs[k][i];
        if (same) {
          w.remap[i] = static_cast<Index>(r);
          merged = true;
          break;
        }
      }
      if (!merged) list.push_back(i);
    }
  }
  w.compact.assign(nv, -1);
  for (size_t i = 0; i < nv; ++i)
    if (w.remap[i] == static_cast<Index>(i)) w.compact[i] = w.kept++;
  return w;
}

/// extras.breastfit.name, else the mesh's, the node's or the file's name.
std::string Loader::model_name() const {
  if (bf_ && bf_->contains("name") && (*bf_)["name"].is_string()) return (*bf_)["name"].get<std::string>();
  if (!mesh_->name.empty()) return mesh_->name;
  const tg::Node& node = g_.nodes[mesh_node_];
  if (!node.name.empty()) return node.name;
  return std::filesystem::path(path_).stem().string();
}

/// Appends `name`, or name_2, name_3, ... when it is taken, to `used`; returns what was added.
std::string unique_name(const std::string& name, std::set<std::string>& used) {
  std::string unique = name;
  for (int s = 2; !used.insert(unique).second; ++s) unique = name + "_" + std::to_string(s);
  return unique;
}

void Loader::add_bones(const Skeleton& sk, RiggedModel& model) const {
  const int nb = static_cast<int>(sk.bone_joint.size());
  std::set<std::string> used_names;
  for (int b = 0; b < nb; ++b) {
    Bone bone;
    if (skin_) {
      bone = joint_bone(sk.bone_joint[b]);
    } else {
      bone.name = "root";
      bone.pivot = model.rest.V.colwise().mean().transpose();
    }
    bone.name = unique_name(bone.name, used_names);
    if (sk.bone_parent[b] >= 0) bone.parent = sk.bone_parent[b];
    model.bones.push_back(bone);
  }
}

/// The bone of one skin joint: its node's name and world position, overridden by the joint
/// node's extras.breastfit (pivot, axes, scale bounds and stiffness).
Bone Loader::joint_bone(int joint) const {
  Bone bone;
  const int jn = skin_->joints[joint];
  bone.name = g_.nodes[jn].name.empty() ? "joint" + std::to_string(joint) : g_.nodes[jn].name;
  bone.pivot = gltf_to_model(world_[jn].topRightCorner<3, 1>());
  const json ex = to_json(g_.nodes[jn].extras);
  if (!ex.is_object() || !ex.contains("breastfit")) return bone;
  const json& e = ex["breastfit"];
  const std::string w = "joint '" + bone.name + "' extras.breastfit";
  if (!e.is_object()) fail(w + " must be an object");
  if (e.contains("pivot")) bone.pivot = json_vec3(e["pivot"], w + ".pivot");
  if (e.contains("axes")) {
    const json& ax = e["axes"];
    if (!ax.is_array() || ax.size() != 3) fail(w + ".axes must be an array of 3 axis vectors");
    for (int c = 0; c < 3; ++c) bone.axes.col(c) = json_vec3(ax[c], w + ".axes[" + std::to_string(c) + "]");
  }
  if (e.contains("scale_lo")) bone.scale_lo = json_vec3(e["scale_lo"], w + ".scale_lo");
  if (e.contains("scale_hi")) bone.scale_hi = json_vec3(e["scale_hi"], w + ".scale_hi");
  if (e.contains("scale_stiffness")) bone.scale_stiffness = json_vec3(e["scale_stiffness"], w + ".scale_stiffness");
  return bone;
}

void Loader::add_weights(const RawMesh& raw, const Skeleton& sk, const Welding& w, RiggedModel& model) const {
  std::vector<Eigen::Triplet<double, Index>> trips;
  for (size_t i = 0; i < raw.positions.size(); ++i) {
    if (w.compact[i] < 0) continue;
    for (const auto& [j, wt] : raw.influences[i]) trips.emplace_back(w.compact[i], sk.joint_bone[j], wt);
  }
  model.weights.resize(w.kept, static_cast<Index>(sk.bone_joint.size()));
  model.weights.setFromTriplets(trips.begin(), trips.end());
  model.weights.makeCompressed();
}

/// One blendshape per morph target: named by mesh.extras.targetNames (else target_k, made
/// unique), bounded by extras.breastfit.blendshape_bounds (else Blender's [0, 1]), with the
/// kept vertices it moves.
void Loader::add_blendshapes(const ModelFrameVertices& mv, const Welding& w, RiggedModel& model) const {
  std::vector<std::string> target_names;
  if (mesh_extras_.is_object() && mesh_extras_.contains("targetNames") && mesh_extras_["targetNames"].is_array()) {
    for (const auto& n : mesh_extras_["targetNames"]) target_names.push_back(n.is_string() ? n.get<std::string>() : "");
  }
  json bounds = json::object();
  if (bf_ && bf_->contains("blendshape_bounds")) {
    bounds = (*bf_)["blendshape_bounds"];
    if (!bounds.is_object()) fail("mesh.extras.breastfit.blendshape_bounds must be an object");
  }
  std::set<std::string> used_names;
  const size_t nv = w.compact.size();
  for (size_t k = 0; k < mv.disp.size(); ++k) {
    Blendshape s;
    s.name = unique_name((k < target_names.size() && !target_names[k].empty()) ? target_names[k]
                                                                              : "target_" + std::to_string(k),
                         used_names);
    s.lo = kDefaultShapeLo;
    s.hi = kDefaultShapeHi;
    if (bounds.contains(s.name)) {
      const json& b = bounds[s.name];
      if (!b.is_array() || b.size() != 2 || !b[0].is_number() || !b[1].is_number())
        fail("blendshape_bounds['" + s.name + "'] must be [lo, hi]");
      s.lo = b[0].get<double>();
      s.hi = b[1].get<double>();
    }
    std::vector<Index> verts;
    for (size_t i = 0; i < nv; ++i)
      if (w.compact[i] >= 0 && mv.disp[k][i] != Vec3::Zero()) verts.push_back(w.compact[i]);
    s.vertices = verts;  // ascending: compact indices grow with i
    s.displacements.resize(static_cast<Index>(verts.size()), 3);
    Index r = 0;
    for (size_t i = 0; i < nv; ++i)
      if (w.compact[i] >= 0 && mv.disp[k][i] != Vec3::Zero()) s.displacements.row(r++) = mv.disp[k][i].transpose();
    model.blendshapes.push_back(std::move(s));
  }
}

/// Landmarks, drawings and regions of extras.breastfit.
void Loader::add_annotations(RiggedModel& model) const {
  for (const json& l : extras_array("landmarks")) {
    ModelLandmark lm;
    lm.name = item_name(l, "landmark");
    if (!l.contains("face") || !l.contains("bary")) fail("landmark '" + lm.name + "' needs 'face' and 'bary'");
    lm.point = surface_point(l["face"], l["bary"], "landmark '" + lm.name + "'");
    model.landmarks.push_back(lm);
  }
  for (const json& d : extras_array("drawings")) {
    Drawing dr;
    dr.name = item_name(d, "drawing");
    dr.closed = d.value("closed", false);
    if (!d.contains("points") || !d["points"].is_array()) fail("drawing '" + dr.name + "' needs 'points'");
    for (const json& p : d["points"]) {
      if (!p.is_array() || p.size() != 4) fail("drawing '" + dr.name + "': each point is [face, b0, b1, b2]");
      dr.points.push_back(surface_point(p[0], json::array({p[1], p[2], p[3]}), "drawing '" + dr.name + "'"));
    }
    model.drawings.push_back(std::move(dr));
  }
  for (const json& r : extras_array("regions")) {
    VertexRegion reg;
    reg.name = item_name(r, "region");
    if (!r.contains("vertices") || !r["vertices"].is_array()) fail("region '" + reg.name + "' needs 'vertices'");
    for (const json& v : r["vertices"]) {
      if (!v.is_number_integer()) fail("region '" + reg.name + "': vertex indices must be integers");
      reg.vertices.push_back(v.get<Index>());
    }
    model.regions.push_back(std::move(reg));
  }
}

SurfacePoint Loader::surface_point(const json& face, const json& bary, const std::string& what) const {
  if (!face.is_number_integer()) fail(what + ": face must be an integer");
  SurfacePoint p;
  p.face = face.get<Index>();
  p.bary = json_vec3(bary, what + ": bary");
  return p;
}

/// extras.breastfit[key] (an array), or an empty array when absent.
json Loader::extras_array(const char* key) const {
  if (!bf_->contains(key)) return json::array();
  if (!(*bf_)[key].is_array()) fail(std::string("mesh.extras.breastfit.") + key + " must be an array");
  return (*bf_)[key];
}

std::string Loader::item_name(const json& item, const std::string& what) const {
  if (!item.is_object() || !item.contains("name") || !item["name"].is_string())
    fail(what + " must be an object with a string 'name'");
  return item["name"].get<std::string>();
}

// =============================================================================================
// Saving

class BufferBuilder {
 public:
  explicit BufferBuilder(tg::Model& g) : g_(g) {}

  /// Appends raw bytes as a new buffer view (4-byte aligned); returns its index.
  int add_view(const void* data, size_t bytes, int target) {
    while (data_.size() % 4 != 0) data_.push_back(0);
    tg::BufferView bv;
    bv.buffer = 0;
    bv.byteOffset = data_.size();
    bv.byteLength = bytes;
    bv.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    data_.insert(data_.end(), p, p + bytes);
    g_.bufferViews.push_back(bv);
    return static_cast<int>(g_.bufferViews.size()) - 1;
  }

  int add_accessor(int view, int component_type, size_t count, int type, std::vector<double> min = {},
                   std::vector<double> max = {}) {
    tg::Accessor a;
    a.bufferView = view;
    a.componentType = component_type;
    a.count = count;
    a.type = type;
    a.minValues = std::move(min);
    a.maxValues = std::move(max);
    g_.accessors.push_back(a);
    return static_cast<int>(g_.accessors.size()) - 1;
  }

  int add_vec3_floats(const std::vector<float>& xyz, int target) {
    const size_t n = xyz.size() / 3;
    std::vector<double> lo(3, 0.0), hi(3, 0.0);
    for (int c = 0; c < 3 && n > 0; ++c) {
      lo[c] = hi[c] = xyz[c];
      for (size_t i = 0; i < n; ++i) {
        lo[c] = std::min<double>(lo[c], xyz[3 * i + c]);
        hi[c] = std::max<double>(hi[c], xyz[3 * i + c]);
      }
    }
    const int view = add_view(xyz.data(), xyz.size() * sizeof(float), target);
    return add_accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, n, TINYGLTF_TYPE_VEC3, lo, hi);
  }

  void finish() {
    tg::Buffer buf;
    buf.data = std::move(data_);
    g_.buffers.push_back(std::move(buf));
  }

 private:
  tg::Model& g_;
  std::vector<unsigned char> data_;
};

/// Influences per vertex, strongest first (ties keep the bone order).
/// \throws InvalidInput when a vertex has more than kMaxInfluences
std::vector<Influences> influences_strongest_first(const RiggedModel& model) {
  const Index nv = model.num_vertices();
  std::vector<Influences> inf(nv);
  for (Index i = 0; i < nv; ++i) {
    for (SkinWeights::InnerIterator it(model.weights, i); it; ++it)
      if (it.value() > 0) inf[i].emplace_back(static_cast<int>(it.col()), it.value());
    if (static_cast<int>(inf[i].size()) > kMaxInfluences)
      throw InvalidInput("save_gltf: vertex " + std::to_string(i) + " has " + std::to_string(inf[i].size()) +
                         " skin influences, glTF export supports at most 8");
    std::stable_sort(inf[i].begin(), inf[i].end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  }
  return inf;
}

/// POSITION, NORMAL and the triangle indices of the rest mesh (glTF frame, float32). glTF
/// wants unit normals everywhere: a vertex without one (a zero row of mesh::vertex_normals)
/// gets the model's +Z.
void add_geometry(const RiggedModel& model, BufferBuilder& bb, tg::Primitive& prim) {
  const Index nv = model.num_vertices();
  std::vector<float> pos(3 * nv), nrm(3 * nv);
  const Points N = mesh::vertex_normals(model.rest.V, model.rest.F);
  for (Index i = 0; i < nv; ++i) {
    const Vec3 q = model_to_gltf(model.rest.V.row(i).transpose());
    const Vec3 ni = N.row(i).squaredNorm() > 0 ? Vec3(N.row(i).transpose()) : Vec3::UnitZ();
    const Vec3 n = model_to_gltf(ni).normalized();
    for (int c = 0; c < 3; ++c) {
      pos[3 * i + c] = static_cast<float>(q[c]);
      nrm[3 * i + c] = static_cast<float>(n[c]);
    }
  }
  prim.attributes["POSITION"] = bb.add_vec3_floats(pos, TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.attributes["NORMAL"] = bb.add_vec3_floats(nrm, TINYGLTF_TARGET_ARRAY_BUFFER);
  std::vector<uint32_t> idx(3 * model.rest.num_faces());
  for (Index f = 0; f < model.rest.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) idx[3 * f + c] = static_cast<uint32_t>(model.rest.F(f, c));
  const int view = bb.add_view(idx.data(), idx.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  prim.indices = bb.add_accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, idx.size(), TINYGLTF_TYPE_SCALAR);
}

/// JOINTS_k / WEIGHTS_k: one set per 4 influences (a second set when a vertex has more than 4).
void add_skin_attributes(const std::vector<Influences>& inf, BufferBuilder& bb, tg::Primitive& prim) {
  const Index nv = static_cast<Index>(inf.size());
  int max_inf = 1;
  for (const auto& v : inf) max_inf = std::max(max_inf, static_cast<int>(v.size()));
  const int sets = max_inf > 4 ? 2 : 1;
  for (int set = 0; set < sets; ++set) {
    std::vector<uint16_t> joints(4 * nv, 0);
    std::vector<float> weights(4 * nv, 0.0f);
    for (Index i = 0; i < nv; ++i) {
      for (int c = 0; c < 4; ++c) {
        const size_t e = static_cast<size_t>(4 * set + c);
        if (e >= inf[i].size()) break;
        joints[4 * i + c] = static_cast<uint16_t>(inf[i][e].first);
        weights[4 * i + c] = static_cast<float>(inf[i][e].second);
      }
    }
    const int jv = bb.add_view(joints.data(), joints.size() * 2, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["JOINTS_" + std::to_string(set)] =
        bb.add_accessor(jv, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, nv, TINYGLTF_TYPE_VEC4);
    const int wv = bb.add_view(weights.data(), weights.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["WEIGHTS_" + std::to_string(set)] =
        bb.add_accessor(wv, TINYGLTF_COMPONENT_TYPE_FLOAT, nv, TINYGLTF_TYPE_VEC4);
  }
}

/// Morph targets: one sparse POSITION accessor per blendshape (glTF frame, float32).
void add_morph_targets(const RiggedModel& model, tg::Model& g, BufferBuilder& bb, tg::Primitive& prim) {
  for (const Blendshape& s : model.blendshapes) {
    const size_t n = s.vertices.size();
    std::vector<double> lo(3, 0.0), hi(3, 0.0);
    std::vector<uint32_t> idx(n);
    std::vector<float> val(3 * n);
    for (size_t r = 0; r < n; ++r) {
      idx[r] = static_cast<uint32_t>(s.vertices[r]);
      const Vec3 d = model_to_gltf(s.displacements.row(static_cast<Index>(r)).transpose());
      for (int c = 0; c < 3; ++c) {
        val[3 * r + c] = static_cast<float>(d[c]);
        lo[c] = std::min<double>(lo[c], val[3 * r + c]);
        hi[c] = std::max<double>(hi[c], val[3 * r + c]);
      }
    }
    const int acc = bb.add_accessor(-1, TINYGLTF_COMPONENT_TYPE_FLOAT, model.num_vertices(), TINYGLTF_TYPE_VEC3, lo, hi);
    if (n > 0) {
      tg::Accessor& a = g.accessors[acc];
      a.sparse.isSparse = true;
      a.sparse.count = static_cast<int>(n);
      a.sparse.indices.bufferView = bb.add_view(idx.data(), n * 4, 0);
      a.sparse.indices.byteOffset = 0;
      a.sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
      a.sparse.values.bufferView = bb.add_view(val.data(), val.size() * 4, 0);
      a.sparse.values.byteOffset = 0;
    }
    prim.targets.push_back({{"POSITION", acc}});
  }
}

/// mesh.extras: the blendshape names (targetNames, as Blender reads them) and the breastfit
/// object (format version, name, units, frame, blendshape bounds, landmarks, drawings, regions).
json mesh_extras_json(const RiggedModel& model) {
  json target_names = json::array();
  json bounds = json::object();
  for (const Blendshape& s : model.blendshapes) {
    target_names.push_back(s.name);
    bounds[s.name] = json::array({s.lo, s.hi});
  }
  json bf;
  bf["version"] = kFormatVersion;
  bf["name"] = model.name;
  bf["units"] = "mm";
  bf["frame"] = "LPS";
  bf["blendshape_bounds"] = bounds;
  bf["landmarks"] = json::array();
  for (const auto& l : model.landmarks)
    bf["landmarks"].push_back({{"name", l.name}, {"face", l.point.face}, {"bary", vec_json(l.point.bary)}});
  bf["drawings"] = json::array();
  for (const auto& d : model.drawings) {
    json pts = json::array();
    for (const auto& sp : d.points) pts.push_back(json::array({sp.face, sp.bary[0], sp.bary[1], sp.bary[2]}));
    bf["drawings"].push_back({{"name", d.name}, {"closed", d.closed}, {"points", pts}});
  }
  bf["regions"] = json::array();
  for (const auto& r : model.regions) bf["regions"].push_back({{"name", r.name}, {"vertices", r.vertices}});
  return json{{"targetNames", target_names}, {"breastfit", bf}};
}

/// The joint node of bone j: translation from its parent's pivot (glTF frame) and the bone's
/// model-frame data in extras.breastfit.
tg::Node joint_node(const RiggedModel& model, int j) {
  const Bone& b = model.bones[j];
  tg::Node jn;
  jn.name = b.name;
  const Vec3 world = model_to_gltf(b.pivot);
  const Vec3 local = b.parent ? Vec3(world - model_to_gltf(model.bones[*b.parent].pivot)) : world;
  jn.translation = {local.x(), local.y(), local.z()};
  json ex;
  ex["pivot"] = vec_json(b.pivot);
  ex["axes"] = json::array({vec_json(b.axes.col(0)), vec_json(b.axes.col(1)), vec_json(b.axes.col(2))});
  ex["scale_lo"] = vec_json(b.scale_lo);
  ex["scale_hi"] = vec_json(b.scale_hi);
  if (b.scale_stiffness != Vec3::Ones()) ex["scale_stiffness"] = vec_json(b.scale_stiffness);
  jn.extras = to_value(json{{"breastfit", ex}});
  return jn;
}

/// Nodes 0 = mesh, 1 = Armature, 2.. = joints, and the skin (inverse bind matrices: translation
/// by −pivot).
void add_nodes_and_skin(const RiggedModel& model, tg::Model& g, BufferBuilder& bb) {
  const int nb = model.num_bones();
  tg::Node mesh_node;
  mesh_node.name = model.name;
  mesh_node.mesh = 0;
  mesh_node.skin = 0;
  g.nodes.push_back(mesh_node);
  tg::Node armature;
  armature.name = "Armature";
  g.nodes.push_back(armature);
  tg::Skin skin;
  skin.name = "Armature";
  std::vector<float> ibm(16 * nb, 0.0f);
  for (int j = 0; j < nb; ++j) {
    const Bone& b = model.bones[j];
    g.nodes.push_back(joint_node(model, j));
    const int node_index = 2 + j;
    skin.joints.push_back(node_index);
    if (b.parent) g.nodes[2 + *b.parent].children.push_back(node_index);
    else g.nodes[1].children.push_back(node_index);
    // Inverse bind matrix: translation by −pivot (column-major).
    const Vec3 world = model_to_gltf(b.pivot);
    for (int d = 0; d < 4; ++d) ibm[16 * j + 5 * d] = 1.0f;
    for (int c = 0; c < 3; ++c) ibm[16 * j + 12 + c] = static_cast<float>(-world[c]);
  }
  const int view = bb.add_view(ibm.data(), ibm.size() * 4, 0);
  skin.inverseBindMatrices = bb.add_accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, nb, TINYGLTF_TYPE_MAT4);
  skin.skeleton = 1;
  g.skins.push_back(skin);
}

/// Problems tinygltf reports badly or not at all, found in the file's JSON: a glTF 1.0 file and
/// a skin without joints. Anything else is left to tinygltf.
void check_gltf_json(const std::filesystem::path& path, const std::string& ext) {
  const std::string p = path.string();
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string_view text = bytes;
  if (ext == ".glb") {
    if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) return;
    const auto u32 = [&](std::size_t at) {
      std::uint32_t v = 0;
      for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(k)]);
      return v;
    };
    if (u32(4) == 1) throw IoError(p, "glTF 1.0 is not supported (2.0 required): re-export the file as glTF 2.0");
    const std::uint32_t length = u32(12);
    if (length > bytes.size() - 20) return;
    text = text.substr(20, length);
  }
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) return;
  if (const auto a = j.find("asset"); a != j.end() && a->is_object()) {
    const auto v = a->find("version");
    if (v != a->end() && v->is_string() && v->get<std::string>().rfind("1", 0) == 0)
      throw IoError(p, "glTF " + v->get<std::string>() + " is not supported (2.0 required): re-export the file as glTF 2.0");
  }
  if (const auto skins = j.find("skins"); skins != j.end() && skins->is_array()) {
    for (std::size_t i = 0; i < skins->size(); ++i) {
      const json& skin = (*skins)[i];
      const auto joints = skin.is_object() ? skin.find("joints") : skin.end();
      if (!skin.is_object() || joints == skin.end() || !joints->is_array() || joints->empty()) {
        const std::string name = skin.is_object() && skin.contains("name") && skin["name"].is_string()
                                     ? " ('" + skin["name"].get<std::string>() + "')"
                                     : "";
        throw IoError(p, "skin " + std::to_string(i) + name + " has no joints (a skin needs a non-empty \"joints\" list)");
      }
    }
  }
}

}  // namespace

RiggedModel load_gltf(const std::filesystem::path& path, const std::string& mesh) {
  const std::string p = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(p, "no such file");
  if (std::filesystem::is_directory(path, ec)) throw IoError(p, "is a directory, not a glTF file");
  const std::string ext = lower_extension(path);
  if (ext != ".gltf" && ext != ".glb") throw IoError(p, "unsupported template extension '" + ext + "' (use .gltf or .glb)");
  check_gltf_json(path, ext);
  tg::TinyGLTF loader;
  tg::Model g;
  std::string err, warn;
  bool ok = false;
  try {
    ok = ext == ".glb" ? loader.LoadBinaryFromFile(&g, &err, &warn, p) : loader.LoadASCIIFromFile(&g, &err, &warn, p);
  } catch (const std::exception& e) {
    throw IoError(p, std::string("invalid glTF: ") + e.what());
  }
  if (!ok) {
    std::string first = err.substr(0, err.find('\n'));
    if (first.empty()) first = "unknown error";
    throw IoError(p, "invalid glTF: " + first);
  }
  Loader l(p, g, mesh);
  try {
    return l.run();
  } catch (const json::exception& e) {
    throw IoError(p, std::string("malformed extras: ") + e.what());
  }
}

void save_gltf(const std::filesystem::path& path, const RiggedModel& model) {
  model.validate();
  const std::string p = path.string();
  const std::string ext = lower_extension(path);
  if (ext != ".gltf" && ext != ".glb") throw IoError(p, "unsupported template extension '" + ext + "' (use .gltf or .glb)");
  const std::vector<Influences> inf = influences_strongest_first(model);

  tg::Model g;
  g.asset.version = "2.0";
  g.asset.generator = "breastfit";
  BufferBuilder bb(g);
  tg::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  add_geometry(model, bb, prim);
  add_skin_attributes(inf, bb, prim);
  add_morph_targets(model, g, bb, prim);
  tg::Mesh mesh;
  mesh.name = model.name;
  mesh.primitives.push_back(prim);
  mesh.weights.assign(model.blendshapes.size(), 0.0);
  mesh.extras = to_value(mesh_extras_json(model));
  g.meshes.push_back(std::move(mesh));
  add_nodes_and_skin(model, g, bb);
  bb.finish();

  tg::Scene scene;
  scene.name = "Scene";
  scene.nodes = {0, 1};
  g.scenes.push_back(scene);
  g.defaultScene = 0;

  const bool binary = ext == ".glb";
  tg::TinyGLTF writer;
  bool ok = false;
  try {
    ok = writer.WriteGltfSceneToFile(&g, p, /*embedImages=*/true, /*embedBuffers=*/true, /*prettyPrint=*/!binary,
                                     /*writeBinary=*/binary);
  } catch (const std::exception& e) {
    throw IoError(p, std::string("cannot write glTF: ") + e.what());
  }
  if (!ok) throw IoError(p, "cannot write the file");
}

}  // namespace breastfit::model
