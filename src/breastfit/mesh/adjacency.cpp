#include "breastfit/mesh/adjacency.h"

#include <algorithm>

#include "breastfit/mesh/triangle_indices.h"

namespace breastfit::mesh {
namespace {

/// True when corner k of triangle f repeats an earlier corner of the same triangle.
bool repeats_earlier_corner(const Triangles& F, Eigen::Index f, int k) {
  for (int j = 0; j < k; ++j)
    if (F(f, j) == F(f, k)) return true;
  return false;
}

/// offsets[v + 1] holds the count of row v; turns counts into row starts (prefix sums).
void counts_to_offsets(std::vector<Index>& offsets) {
  for (size_t v = 1; v < offsets.size(); ++v) offsets[v] += offsets[v - 1];
}

}  // namespace

bool AdjacencyLists::contains(Index r, Index x) const {
  const std::span<const Index> row = (*this)[r];
  return std::binary_search(row.begin(), row.end(), x);
}

AdjacencyLists vertex_neighbours(const Triangles& F, Index num_vertices) {
  check_triangle_indices(F, num_vertices);
  const auto nv = static_cast<size_t>(num_vertices);
  // Every corner lists its two triangle neighbours (with repeats), then each row is sorted,
  // deduplicated and stripped of the vertex itself.
  AdjacencyLists raw;
  raw.offsets.assign(nv + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) raw.offsets[static_cast<size_t>(F(f, k)) + 1] += 2;
  counts_to_offsets(raw.offsets);
  raw.items.resize(static_cast<size_t>(raw.offsets.back()));
  std::vector<Index> fill(raw.offsets.begin(), raw.offsets.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      Index& at = fill[static_cast<size_t>(F(f, k))];
      raw.items[static_cast<size_t>(at++)] = F(f, (k + 1) % 3);
      raw.items[static_cast<size_t>(at++)] = F(f, (k + 2) % 3);
    }
  AdjacencyLists out;
  out.offsets.assign(nv + 1, 0);
  out.items.reserve(raw.items.size() / 2);
  for (Index v = 0; v < num_vertices; ++v) {
    Index* b = raw.items.data() + raw.offsets[static_cast<size_t>(v)];
    Index* e = raw.items.data() + raw.offsets[static_cast<size_t>(v) + 1];
    std::sort(b, e);
    e = std::unique(b, e);
    for (const Index* p = b; p != e; ++p)
      if (*p != v) out.items.push_back(*p);
    out.offsets[static_cast<size_t>(v) + 1] = static_cast<Index>(out.items.size());
  }
  return out;
}

AdjacencyLists vertex_neighbours(const TriangleMesh& mesh) {
  return vertex_neighbours(mesh.F, mesh.num_vertices());
}

AdjacencyLists vertex_faces(const Triangles& F, Index num_vertices) {
  check_triangle_indices(F, num_vertices);
  AdjacencyLists out;
  out.offsets.assign(static_cast<size_t>(num_vertices) + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (!repeats_earlier_corner(F, f, k)) ++out.offsets[static_cast<size_t>(F(f, k)) + 1];
  counts_to_offsets(out.offsets);
  out.items.resize(static_cast<size_t>(out.offsets.back()));
  std::vector<Index> fill(out.offsets.begin(), out.offsets.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)  // faces in ascending order: rows come out sorted
    for (int k = 0; k < 3; ++k)
      if (!repeats_earlier_corner(F, f, k))
        out.items[static_cast<size_t>(fill[static_cast<size_t>(F(f, k))]++)] = static_cast<Index>(f);
  return out;
}

AdjacencyLists vertex_faces(const TriangleMesh& mesh) {
  return vertex_faces(mesh.F, mesh.num_vertices());
}

std::vector<std::array<Index, 2>> unique_edges(const Triangles& F, Index num_vertices) {
  const AdjacencyLists nbr = vertex_neighbours(F, num_vertices);
  std::vector<std::array<Index, 2>> edges;
  edges.reserve(nbr.items.size() / 2);
  for (Index a = 0; a < num_vertices; ++a)
    for (const Index b : nbr[a])
      if (a < b) edges.push_back({a, b});
  return edges;
}

}  // namespace breastfit::mesh
