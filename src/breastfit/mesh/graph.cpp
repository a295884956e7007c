#include "breastfit/mesh/graph.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <string>
#include <utility>

#include "breastfit/core/errors.h"

namespace breastfit::mesh {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Min-heap of (distance or estimate, vertex); ties pop the lower vertex first.
using Item = std::pair<double, Index>;
using MinHeap = std::priority_queue<Item, std::vector<Item>, std::greater<Item>>;

double edge_length(const Points& V, Index a, Index b) { return (V.row(a) - V.row(b)).norm(); }

}  // namespace

std::vector<double> edge_distances(const Points& V, const AdjacencyLists& neighbours,
                                   const std::vector<Index>& sources, double max_distance) {
  const Index nv = static_cast<Index>(V.rows());
  if (neighbours.num_rows() != nv)
    throw InvalidInput("edge_distances: the adjacency has " + std::to_string(neighbours.num_rows()) +
                       " rows for " + std::to_string(nv) + " vertices");
  std::vector<double> dist(static_cast<size_t>(nv), kInf);
  MinHeap heap;
  for (const Index s : sources) {
    if (s < 0 || s >= nv)
      throw InvalidInput("edge_distances: source vertex " + std::to_string(s) + " outside [0, " +
                         std::to_string(nv) + ")");
    if (dist[static_cast<size_t>(s)] > 0) {
      dist[static_cast<size_t>(s)] = 0;
      heap.push({0.0, s});
    }
  }
  while (!heap.empty()) {
    const auto [d, v] = heap.top();
    heap.pop();
    if (d > dist[static_cast<size_t>(v)]) continue;  // stale entry
    for (const Index w : neighbours[v]) {
      const double dw = d + edge_length(V, v, w);
      if (dw <= max_distance && dw < dist[static_cast<size_t>(w)]) {
        dist[static_cast<size_t>(w)] = dw;
        heap.push({dw, w});
      }
    }
  }
  return dist;
}

EdgePathFinder::EdgePathFinder(const Points& V, const AdjacencyLists& neighbours)
    : V_(V),
      nbr_(neighbours),
      g_(static_cast<size_t>(V.rows()), kInf),
      parent_(static_cast<size_t>(V.rows()), -1) {
  if (neighbours.num_rows() != static_cast<Index>(V.rows()))
    throw InvalidInput("EdgePathFinder: the adjacency has " + std::to_string(neighbours.num_rows()) +
                       " rows for " + std::to_string(V.rows()) + " vertices");
}

std::vector<Index> EdgePathFinder::path(Index from, Index to, int max_expansions) {
  const Vec3 target = V_.row(to).transpose();
  auto estimate = [&](Index v) { return (V_.row(v).transpose() - target).norm(); };
  g_[static_cast<size_t>(from)] = 0;
  parent_[static_cast<size_t>(from)] = -1;
  touched_.push_back(from);
  MinHeap open;
  open.push({estimate(from), from});
  int expansions = 0;
  bool found = false;
  while (!open.empty() && expansions < max_expansions) {
    const auto [f, v] = open.top();
    open.pop();
    if (v == to) {
      found = true;
      break;
    }
    const double gv = g_[static_cast<size_t>(v)];
    if (f > gv + estimate(v) + 1e-12) continue;  // stale entry
    ++expansions;
    for (const Index w : nbr_[v]) {
      const double gw = gv + edge_length(V_, v, w);
      if (gw < g_[static_cast<size_t>(w)]) {
        if (!std::isfinite(g_[static_cast<size_t>(w)])) touched_.push_back(w);
        g_[static_cast<size_t>(w)] = gw;
        parent_[static_cast<size_t>(w)] = v;
        open.push({gw + estimate(w), w});
      }
    }
  }
  std::vector<Index> out;
  if (found)
    for (Index v = to; v != from; v = parent_[static_cast<size_t>(v)]) out.push_back(v);
  std::reverse(out.begin(), out.end());
  for (const Index v : touched_) g_[static_cast<size_t>(v)] = kInf;
  touched_.clear();
  return out;
}

void flood_fill(const AdjacencyLists& neighbours, Index seed, int label, std::vector<int>& labels,
                const std::vector<char>* blocked) {
  labels[static_cast<size_t>(seed)] = label;
  std::vector<Index> stack{seed};
  while (!stack.empty()) {
    const Index v = stack.back();
    stack.pop_back();
    for (const Index w : neighbours[v]) {
      if (labels[static_cast<size_t>(w)] >= 0) continue;
      if (blocked != nullptr && (*blocked)[static_cast<size_t>(w)]) continue;
      labels[static_cast<size_t>(w)] = label;
      stack.push_back(w);
    }
  }
}

}  // namespace breastfit::mesh
