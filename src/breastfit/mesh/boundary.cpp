#include "breastfit/mesh/boundary.h"

#include <algorithm>
#include <string>

#include "breastfit/core/errors.h"

namespace breastfit::mesh {
namespace {

struct HalfEdge {
  Index lo, hi;  // undirected key
  Index from, to;  // direction in its triangle
};

/// All half-edges of F sorted by undirected key (then by direction, for determinism).
std::vector<HalfEdge> sorted_half_edges(const Triangles& F) {
  std::vector<HalfEdge> h;
  h.reserve(static_cast<size_t>(F.rows()) * 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    // A triangle repeating an index has no area and no proper edges: it does not count.
    if (F(f, 0) == F(f, 1) || F(f, 1) == F(f, 2) || F(f, 0) == F(f, 2)) continue;
    for (int c = 0; c < 3; ++c) {
      const Index a = F(f, c), b = F(f, (c + 1) % 3);
      h.push_back({std::min(a, b), std::max(a, b), a, b});
    }
  }
  std::sort(h.begin(), h.end(), [](const HalfEdge& x, const HalfEdge& y) {
    if (x.lo != y.lo) return x.lo < y.lo;
    if (x.hi != y.hi) return x.hi < y.hi;
    return x.from < y.from;
  });
  return h;
}

/// Calls fn(first, count) for each run of half-edges sharing an undirected edge.
template <class Fn>
void for_each_edge(const std::vector<HalfEdge>& h, Fn&& fn) {
  size_t i = 0;
  while (i < h.size()) {
    size_t j = i + 1;
    while (j < h.size() && h[j].lo == h[i].lo && h[j].hi == h[i].hi) ++j;
    fn(i, j - i);
    i = j;
  }
}

}  // namespace

std::vector<std::array<Index, 2>> boundary_edges(const Triangles& F) {
  const std::vector<HalfEdge> h = sorted_half_edges(F);
  std::vector<std::array<Index, 2>> out;
  for_each_edge(h, [&](size_t first, size_t count) {
    if (count == 1) out.push_back({h[first].from, h[first].to});
  });
  return out;
}

std::vector<bool> boundary_vertices(const Triangles& F, Index num_vertices) {
  std::vector<bool> flags(static_cast<size_t>(std::max<Index>(num_vertices, 0)), false);
  for (const auto& e : boundary_edges(F))
    for (Index v : e) {
      if (v < 0 || v >= num_vertices)
        throw InvalidInput("boundary vertex index " + std::to_string(v) + " outside [0, " +
                           std::to_string(num_vertices) + ")");
      flags[static_cast<size_t>(v)] = true;
    }
  return flags;
}

std::vector<bool> boundary_vertices(const TriangleMesh& mesh) {
  return boundary_vertices(mesh.F, mesh.num_vertices());
}

std::vector<std::vector<Index>> boundary_loops(const Triangles& F) {
  const std::vector<std::array<Index, 2>> edges = boundary_edges(F);
  const size_t m = edges.size();
  // Incidence lists: vertex -> boundary edges touching it (CSR over a sorted (vertex, edge) list).
  std::vector<std::pair<Index, Index>> inc;
  inc.reserve(2 * m);
  for (size_t e = 0; e < m; ++e) {
    inc.push_back({edges[e][0], static_cast<Index>(e)});
    inc.push_back({edges[e][1], static_cast<Index>(e)});
  }
  std::sort(inc.begin(), inc.end());
  auto incident = [&](Index v) {
    auto lo = std::lower_bound(inc.begin(), inc.end(), std::make_pair(v, Index(-1)));
    auto hi = std::lower_bound(inc.begin(), inc.end(), std::make_pair(v + 1, Index(-1)));
    return std::make_pair(lo, hi);
  };

  std::vector<char> used(m, 0);
  std::vector<std::vector<Index>> loops;
  for (size_t start = 0; start < m; ++start) {
    if (used[start]) continue;
    used[start] = 1;
    const Index first = edges[start][0];
    std::vector<Index> loop{first};
    Index cur = edges[start][1];
    while (cur != first) {
      // Next edge at `cur`: prefer one leaving cur in its triangle's direction, else any unused.
      Index next = -1;
      bool next_forward = false;
      auto [lo, hi] = incident(cur);
      for (auto it = lo; it != hi; ++it) {
        const Index e = it->second;
        if (used[static_cast<size_t>(e)]) continue;
        const bool forward = edges[static_cast<size_t>(e)][0] == cur;
        if (next < 0 || (forward && !next_forward)) {
          next = e;
          next_forward = forward;
        }
      }
      if (next < 0) break;  // open chain
      loop.push_back(cur);
      used[static_cast<size_t>(next)] = 1;
      const auto& ne = edges[static_cast<size_t>(next)];
      cur = ne[0] == cur ? ne[1] : ne[0];
    }
    if (cur != first) loop.push_back(cur);  // keep the dangling end of an open chain
    loops.push_back(std::move(loop));
  }
  return loops;
}

std::vector<std::vector<Index>> boundary_loops(const TriangleMesh& mesh) {
  return boundary_loops(mesh.F);
}

Index count_non_manifold_edges(const Triangles& F) {
  const std::vector<HalfEdge> h = sorted_half_edges(F);
  Index n = 0;
  for_each_edge(h, [&](size_t first, size_t count) {
    if (count > 2) ++n;
  });
  return n;
}

double loop_length(const Points& V, const std::vector<Index>& loop) {
  if (loop.size() < 2) return 0.0;
  double len = 0.0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Index a = loop[i], b = loop[(i + 1) % loop.size()];
    len += (V.row(a) - V.row(b)).norm();
  }
  return len;
}

}  // namespace breastfit::mesh
