#include "breastfit/template/plane_clip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>

#include "breastfit/core/errors.h"

namespace breastfit::templ {
namespace {

struct Work {
  std::vector<Vec3> V;
  std::vector<std::uint32_t> mask;
  std::vector<std::array<Index, 3>> F;
};

void clip_one(Work& w, const CutPlane& cut, std::uint32_t bit) {
  const size_t nv = w.V.size();
  std::vector<double> sd(nv);
  for (size_t v = 0; v < nv; ++v) {
    if (!cut.in_region(w.V[v])) {
      sd[v] = -1e6;
      continue;
    }
    double d = cut.signed_distance(w.V[v]);
    if (std::abs(d) < 1e-7) d = -1e-7;  // on the plane: kept
    sd[v] = d;
  }
  std::map<std::pair<Index, Index>, Index> cache;
  auto cut_point = [&](Index a, Index b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    const double t = sd[a] / (sd[a] - sd[b]);
    Vec3 p = w.V[a] + t * (w.V[b] - w.V[a]);
    p -= cut.signed_distance(p) * cut.normal;  // exactly on the plane
    w.V.push_back(p);
    w.mask.push_back((w.mask[a] & w.mask[b]) | bit);
    const Index id = static_cast<Index>(w.V.size() - 1);
    cache.emplace(key, id);
    return id;
  };
  std::vector<std::array<Index, 3>> out;
  out.reserve(w.F.size());
  for (const auto& f : w.F) {
    int nrem = 0;
    for (int c = 0; c < 3; ++c) nrem += sd[f[c]] > 0;
    if (nrem == 0) {
      out.push_back(f);
    } else if (nrem == 1) {
      int r = 0;
      while (sd[f[r]] <= 0) ++r;
      const Index a = f[r], b = f[(r + 1) % 3], c = f[(r + 2) % 3];
      const Index pab = cut_point(a, b), pac = cut_point(a, c);
      out.push_back({pab, b, c});
      out.push_back({pab, c, pac});
    } else if (nrem == 2) {
      int k = 0;
      while (sd[f[k]] > 0) ++k;
      const Index c = f[k], a = f[(k + 1) % 3], b = f[(k + 2) % 3];
      out.push_back({c, cut_point(c, a), cut_point(b, c)});
    }
  }
  w.F.swap(out);
}

}  // namespace

ClippedMesh clip_by_planes(const TriangleMesh& mesh, const std::vector<CutPlane>& cuts) {
  if (cuts.size() > 32) throw InvalidInput("clip_by_planes: at most 32 cuts");
  Work w;
  w.V.resize(mesh.num_vertices());
  for (Index v = 0; v < mesh.num_vertices(); ++v) w.V[v] = mesh.V.row(v).transpose();
  w.mask.assign(w.V.size(), 0);
  w.F.resize(mesh.num_faces());
  for (Index f = 0; f < mesh.num_faces(); ++f) w.F[f] = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
  for (size_t c = 0; c < cuts.size(); ++c) clip_one(w, cuts[c], 1u << c);

  // Drop degenerate triangles (repeated indices).
  std::vector<std::array<Index, 3>> F;
  for (const auto& f : w.F)
    if (f[0] != f[1] && f[1] != f[2] && f[0] != f[2]) F.push_back(f);

  // Largest connected component (union-find over vertices).
  std::vector<Index> parent(w.V.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](Index x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& f : F) {
    for (int c = 1; c < 3; ++c) {
      const Index a = find(f[0]), b = find(f[c]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<Index> count(w.V.size(), 0);
  for (const auto& f : F) ++count[find(f[0])];
  const Index best = static_cast<Index>(std::max_element(count.begin(), count.end()) - count.begin());
  if (F.empty() || count[best] == 0) throw InvalidInput("clip_by_planes: nothing left after clipping");

  std::vector<Index> remap(w.V.size(), -1);
  ClippedMesh out;
  std::vector<std::array<Index, 3>> kept;
  Index nv = 0;
  for (const auto& f : F) {
    if (find(f[0]) != best) continue;
    std::array<Index, 3> g{};
    for (int c = 0; c < 3; ++c) {
      if (remap[f[c]] < 0) remap[f[c]] = nv++;
      g[c] = remap[f[c]];
    }
    kept.push_back(g);
  }
  out.mesh.V.resize(nv, 3);
  out.on_cut.assign(nv, 0);
  for (size_t v = 0; v < w.V.size(); ++v) {
    if (remap[v] < 0) continue;
    out.mesh.V.row(remap[v]) = w.V[v].transpose();
    out.on_cut[remap[v]] = w.mask[v];
  }
  out.mesh.F.resize(static_cast<Index>(kept.size()), 3);
  for (size_t f = 0; f < kept.size(); ++f)
    for (int c = 0; c < 3; ++c) out.mesh.F(static_cast<Index>(f), c) = kept[f][c];
  return out;
}

}  // namespace breastfit::templ
