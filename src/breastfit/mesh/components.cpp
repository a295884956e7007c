#include "breastfit/mesh/components.h"

#include <algorithm>
#include <numeric>
#include <string>

#include "breastfit/mesh/triangle_indices.h"

namespace breastfit::mesh {
namespace {

Index find_root(std::vector<Index>& parent, Index x) {
  while (parent[static_cast<size_t>(x)] != x) {
    Index& p = parent[static_cast<size_t>(x)];
    p = parent[static_cast<size_t>(p)];  // path halving
    x = p;
  }
  return x;
}

// The union-find forest of the vertices, triangles joining their corners (every root a component's
// or an unused vertex's).
std::vector<Index> union_find(const Triangles& F, Index num_vertices) {
  const size_t nv = static_cast<size_t>(std::max<Index>(num_vertices, 0));
  std::vector<Index> parent(nv);
  std::iota(parent.begin(), parent.end(), Index(0));
  check_triangle_indices(F, num_vertices);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Index r0 = find_root(parent, F(f, 0));
    for (int c = 1; c < 3; ++c) {
      const Index r = find_root(parent, F(f, c));
      if (r != r0) parent[static_cast<size_t>(r)] = r0;
    }
  }
  return parent;
}

}  // namespace

Components connected_components(const Triangles& F, Index num_vertices) {
  const size_t nv = static_cast<size_t>(std::max<Index>(num_vertices, 0));
  const size_t nf = static_cast<size_t>(F.rows());
  std::vector<Index> parent = union_find(F, num_vertices);

  // Provisional component per root, in order of first triangle.
  std::vector<Index> root_to_comp(nv, -1);
  std::vector<Index> face_comp(nf);
  std::vector<Index> face_count;
  std::vector<Index> first_face;
  for (size_t f = 0; f < nf; ++f) {
    const Index r = find_root(parent, F(static_cast<Eigen::Index>(f), 0));
    Index& c = root_to_comp[static_cast<size_t>(r)];
    if (c < 0) {
      c = static_cast<Index>(face_count.size());
      face_count.push_back(0);
      first_face.push_back(static_cast<Index>(f));
    }
    face_comp[f] = c;
    ++face_count[static_cast<size_t>(c)];
  }

  // Renumber by decreasing size (ties: first triangle).
  const size_t k = face_count.size();
  std::vector<Index> order(k);
  std::iota(order.begin(), order.end(), Index(0));
  std::sort(order.begin(), order.end(), [&](Index a, Index b) {
    if (face_count[a] != face_count[b]) return face_count[a] > face_count[b];
    return first_face[a] < first_face[b];
  });
  std::vector<Index> rank(k);
  for (size_t i = 0; i < k; ++i) rank[static_cast<size_t>(order[i])] = static_cast<Index>(i);

  Components out;
  out.face_label.resize(nf);
  out.face_count.resize(k);
  out.vertex_count.assign(k, 0);
  for (size_t i = 0; i < k; ++i) out.face_count[i] = face_count[static_cast<size_t>(order[i])];
  for (size_t f = 0; f < nf; ++f) out.face_label[f] = rank[static_cast<size_t>(face_comp[f])];
  out.vertex_label.assign(nv, std::nullopt);
  for (size_t f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) {
      const auto v = static_cast<size_t>(F(static_cast<Eigen::Index>(f), c));
      if (!out.vertex_label[v]) {
        out.vertex_label[v] = out.face_label[f];
        ++out.vertex_count[static_cast<size_t>(out.face_label[f])];
      }
    }
  return out;
}

Components connected_components(const TriangleMesh& mesh) {
  return connected_components(mesh.F, mesh.num_vertices());
}

std::vector<Index> component_size_per_vertex(const TriangleMesh& mesh) {
  std::vector<Index> parent = union_find(mesh.F, mesh.num_vertices());
  std::vector<Index> at_root(parent.size(), 0);  // an unused vertex is a root no triangle counts
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) ++at_root[static_cast<size_t>(find_root(parent, mesh.F(f, 0)))];
  std::vector<Index> out(parent.size());
  for (size_t v = 0; v < out.size(); ++v) out[v] = at_root[static_cast<size_t>(find_root(parent, static_cast<Index>(v)))];
  return out;
}

}  // namespace breastfit::mesh
