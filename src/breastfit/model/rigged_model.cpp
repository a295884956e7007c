#include "breastfit/model/rigged_model.h"

#include <cmath>
#include <set>
#include <sstream>

#include "breastfit/core/errors.h"

namespace breastfit::model {
namespace {

template <class T>
std::optional<int> find_by_name(const std::vector<T>& items, const std::string& name) {
  for (size_t i = 0; i < items.size(); ++i)
    if (items[i].name == name) return static_cast<int>(i);
  return std::nullopt;
}

[[noreturn]] void fail(const std::string& what) { throw InvalidInput("rigged model: " + what); }

std::string vec_str(const Vec3& v) {
  std::ostringstream s;
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

template <class T>
void check_unique_names(const std::vector<T>& items, const char* kind) {
  std::set<std::string> seen;
  for (const auto& it : items) {
    if (it.name.empty()) fail(std::string(kind) + " with an empty name");
    if (!seen.insert(it.name).second) fail(std::string("duplicate ") + kind + " name '" + it.name + "'");
  }
}

void check_surface_point(const SurfacePoint& p, Index num_faces, const std::string& what) {
  if (p.face < 0 || p.face >= num_faces)
    fail(what + ": face " + std::to_string(p.face) + " out of range [0, " + std::to_string(num_faces) + ")");
  if (!p.bary.allFinite()) fail(what + ": non-finite barycentric coordinates");
  if (std::abs(p.bary.sum() - 1.0) > 1e-6)
    fail(what + ": barycentric coordinates " + vec_str(p.bary) + " do not sum to 1");
  if (p.bary.minCoeff() < -1e-6) fail(what + ": negative barycentric coordinate in " + vec_str(p.bary));
}

}  // namespace

std::optional<int> RiggedModel::bone_index(const std::string& n) const { return find_by_name(bones, n); }
std::optional<int> RiggedModel::blendshape_index(const std::string& n) const {
  return find_by_name(blendshapes, n);
}
std::optional<int> RiggedModel::landmark_index(const std::string& n) const { return find_by_name(landmarks, n); }
std::optional<int> RiggedModel::drawing_index(const std::string& n) const { return find_by_name(drawings, n); }
std::optional<int> RiggedModel::region_index(const std::string& n) const { return find_by_name(regions, n); }

std::vector<Index> RiggedModel::vertices_mostly_moved_by(int bone, double min_weight) const {
  std::vector<Index> out;
  for (Index i = 0; i < weights.outerSize(); ++i)
    for (SkinWeights::InnerIterator it(weights, i); it; ++it)
      if (it.col() == bone && it.value() > min_weight) out.push_back(i);
  return out;
}

void RiggedModel::validate() const {
  const Index nv = num_vertices();
  const Index nf = rest.num_faces();
  const int nb = num_bones();

  // Mesh.
  if (nv == 0) fail("the rest mesh has no vertices");
  if (nf == 0) fail("the rest mesh has no triangles");
  if (!rest.V.allFinite()) fail("the rest mesh has non-finite vertex coordinates");
  for (Index f = 0; f < nf; ++f) {
    for (int c = 0; c < 3; ++c) {
      const Index v = rest.F(f, c);
      if (v < 0 || v >= nv)
        fail("triangle " + std::to_string(f) + " references vertex " + std::to_string(v) + " out of range [0, " +
             std::to_string(nv) + ")");
    }
  }

  // Bones.
  if (nb == 0) fail("no bones");
  check_unique_names(bones, "bone");
  for (int j = 0; j < nb; ++j) {
    const Bone& b = bones[j];
    const std::string who = "bone '" + b.name + "'";
    if (b.parent) {
      if (*b.parent < 0 || *b.parent >= j)
        fail(who + ": parent index " + std::to_string(*b.parent) + " must refer to an earlier bone");
    }
    if (!b.pivot.allFinite()) fail(who + ": non-finite pivot");
    if (!b.axes.allFinite()) fail(who + ": non-finite axes");
    if ((b.axes.transpose() * b.axes - Mat3::Identity()).cwiseAbs().maxCoeff() > 1e-6)
      fail(who + ": rest axes are not orthonormal");
    if (b.axes.determinant() < 0) fail(who + ": rest axes are not right-handed");
    if (!b.scale_lo.allFinite() || !b.scale_hi.allFinite()) fail(who + ": non-finite scale bounds");
    if (b.scale_lo.minCoeff() <= 0) fail(who + ": scale lower bound " + vec_str(b.scale_lo) + " must be > 0");
    if ((b.scale_hi - b.scale_lo).minCoeff() < 0)
      fail(who + ": scale bounds lo " + vec_str(b.scale_lo) + " > hi " + vec_str(b.scale_hi));
    if (!b.scale_stiffness.allFinite() || b.scale_stiffness.minCoeff() <= 0)
      fail(who + ": scale stiffness " + vec_str(b.scale_stiffness) + " must be finite and > 0");
  }

  // Skin weights.
  if (weights.rows() != nv || weights.cols() != nb)
    fail("skin weights are " + std::to_string(weights.rows()) + " by " + std::to_string(weights.cols()) +
         ", expected #vertices " + std::to_string(nv) + " by #bones " + std::to_string(nb));
  for (Index i = 0; i < nv; ++i) {
    double sum = 0;
    for (SkinWeights::InnerIterator it(weights, i); it; ++it) {
      if (!std::isfinite(it.value()) || it.value() < 0)
        fail("skin weight of vertex " + std::to_string(i) + " for bone " + std::to_string(it.col()) +
             " is negative or non-finite");
      sum += it.value();
    }
    if (std::abs(sum - 1.0) > 1e-6)
      fail("skin weights of vertex " + std::to_string(i) + " sum to " + std::to_string(sum) + ", not 1");
  }

  // Blendshapes.
  check_unique_names(blendshapes, "blendshape");
  for (const Blendshape& s : blendshapes) {
    const std::string who = "blendshape '" + s.name + "'";
    if (static_cast<Index>(s.displacements.rows()) != static_cast<Index>(s.vertices.size()))
      fail(who + ": " + std::to_string(s.displacements.rows()) + " displacement rows for " +
           std::to_string(s.vertices.size()) + " vertices");
    for (size_t r = 0; r < s.vertices.size(); ++r) {
      const Index v = s.vertices[r];
      if (v < 0 || v >= nv) fail(who + ": vertex " + std::to_string(v) + " out of range");
      if (r > 0 && v <= s.vertices[r - 1]) fail(who + ": vertex indices are not ascending and unique");
    }
    if (!s.displacements.allFinite()) fail(who + ": non-finite displacements");
    if (!std::isfinite(s.lo) || !std::isfinite(s.hi)) fail(who + ": non-finite bounds");
    if (s.lo > s.hi) fail(who + ": bounds lo " + std::to_string(s.lo) + " > hi " + std::to_string(s.hi));
  }

  // Landmarks, drawings, regions.
  check_unique_names(landmarks, "landmark");
  for (const auto& l : landmarks) check_surface_point(l.point, nf, "landmark '" + l.name + "'");
  check_unique_names(drawings, "drawing");
  for (const auto& d : drawings) {
    if (d.points.empty()) fail("drawing '" + d.name + "' has no points");
    for (size_t k = 0; k < d.points.size(); ++k)
      check_surface_point(d.points[k], nf, "drawing '" + d.name + "' point " + std::to_string(k));
  }
  check_unique_names(regions, "region");
  for (const auto& r : regions) {
    for (Index v : r.vertices)
      if (v < 0 || v >= nv) fail("region '" + r.name + "': vertex " + std::to_string(v) + " out of range");
  }
}

}  // namespace breastfit::model
