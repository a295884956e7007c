#include "breastfit/template/isotropic_remesher.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "breastfit/core/errors.h"

namespace breastfit::templ {
namespace {

using Face = std::array<Index, 3>;

class Remesher {
 public:
  Remesher(const ClippedMesh& in, const BodyField& field, const std::vector<CutPlane>& cuts)
      : field_(field), cuts_(cuts) {
    const Index nv = in.mesh.num_vertices();
    pos_.resize(nv);
    for (Index v = 0; v < nv; ++v) pos_[v] = in.mesh.V.row(v).transpose();
    mask_ = in.on_cut;
    valive_.assign(nv, 1);
    faces_.resize(in.mesh.num_faces());
    falive_.assign(faces_.size(), 1);
    vf_.assign(nv, {});
    for (Index f = 0; f < in.mesh.num_faces(); ++f) {
      faces_[f] = {in.mesh.F(f, 0), in.mesh.F(f, 1), in.mesh.F(f, 2)};
      for (int c = 0; c < 3; ++c) vf_[faces_[f][c]].push_back(f);
    }
    // Cut vertices exactly on their plane(s) and on the surface (the others are projected when
    // they are first smoothed).
    for (Index v = 0; v < nv; ++v)
      if (mask_[v]) pos_[v] = project(pos_[v], mask_[v]);
  }

  void run(const RemeshOptions& o) {
    const double L = o.target_edge_mm;
    const double hi = 4.0 / 3.0 * L, lo = 4.0 / 5.0 * L;
    for (int it = 0; it < o.iterations; ++it) {
      split_long(hi);
      collapse_short(lo, hi);
      flip_valence();
      for (int s = 0; s < o.smoothing_steps; ++s) smooth();
    }
    // Last: remove any sliver left by splitting and a final clean projection.
    flip_valence();
    smooth();
  }

  ClippedMesh result() const {
    std::vector<Index> remap(pos_.size(), -1);
    Index nv = 0;
    // Keep vertices in order of first use by alive faces (deterministic).
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!falive_[f]) continue;
      for (int c = 0; c < 3; ++c)
        if (remap[faces_[f][c]] < 0) remap[faces_[f][c]] = nv++;
    }
    ClippedMesh out;
    out.mesh.V.resize(nv, 3);
    out.on_cut.assign(nv, 0);
    for (size_t v = 0; v < pos_.size(); ++v) {
      if (remap[v] < 0) continue;
      out.mesh.V.row(remap[v]) = pos_[v].transpose();
      out.on_cut[remap[v]] = mask_[v];
    }
    Index nf = 0;
    for (size_t f = 0; f < faces_.size(); ++f) nf += falive_[f];
    out.mesh.F.resize(nf, 3);
    Index k = 0;
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!falive_[f]) continue;
      for (int c = 0; c < 3; ++c) out.mesh.F(k, c) = remap[faces_[f][c]];
      ++k;
    }
    return out;
  }

 private:
  // ---- constraints -------------------------------------------------------------------------
  Vec3 project(const Vec3& p, std::uint32_t mask) const {
    const int bits = std::popcount(mask);
    if (bits == 0) return field_.project(p);
    if (bits == 1) {
      const CutPlane& c = cuts_[std::countr_zero(mask)];
      return field_.project_on_plane(p, c.point, c.normal);
    }
    int first = std::countr_zero(mask);
    const std::uint32_t rest = mask & ~(1u << first);
    const int second = std::countr_zero(rest);
    return field_.project_on_two_planes(p, cuts_[first], cuts_[second]);
  }
  bool is_corner(Index v) const { return std::popcount(mask_[v]) >= 2; }

  // ---- topology helpers --------------------------------------------------------------------
  static bool has(const Face& f, Index v) { return f[0] == v || f[1] == v || f[2] == v; }
  std::vector<Index> edge_faces(Index a, Index b) const {
    std::vector<Index> out;
    for (Index f : vf_[a])
      if (has(faces_[f], b)) out.push_back(f);
    return out;
  }
  static Index third(const Face& f, Index a, Index b) {
    for (int c = 0; c < 3; ++c)
      if (f[c] != a && f[c] != b) return f[c];
    return -1;
  }
  std::vector<Index> ring(Index v) const {
    std::vector<Index> r;
    for (Index f : vf_[v])
      for (int c = 0; c < 3; ++c)
        if (faces_[f][c] != v) r.push_back(faces_[f][c]);
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    return r;
  }
  int valence(Index v) const { return static_cast<int>(ring(v).size()); }
  bool is_boundary_edge(Index a, Index b) const { return edge_faces(a, b).size() == 1; }
  static void erase_value(std::vector<Index>& xs, Index x) {
    auto it = std::find(xs.begin(), xs.end(), x);
    if (it != xs.end()) xs.erase(it);
  }
  Vec3 face_normal_raw(const Face& f) const {
    return (pos_[f[1]] - pos_[f[0]]).cross(pos_[f[2]] - pos_[f[0]]);
  }
  std::vector<std::pair<Index, Index>> edges() const {
    std::vector<std::pair<Index, Index>> e;
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!falive_[f]) continue;
      for (int c = 0; c < 3; ++c) {
        const Index a = faces_[f][c], b = faces_[f][(c + 1) % 3];
        e.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
    std::sort(e.begin(), e.end());
    e.erase(std::unique(e.begin(), e.end()), e.end());
    return e;
  }

  // ---- operations --------------------------------------------------------------------------
  void split_long(double hi) {
    for (const auto& [a, b] : edges()) {
      if (!valive_[a] || !valive_[b]) continue;
      if ((pos_[a] - pos_[b]).norm() <= hi) continue;
      const auto ef = edge_faces(a, b);
      if (ef.empty()) continue;
      const bool boundary = ef.size() == 1;
      std::uint32_t m = boundary ? (mask_[a] & mask_[b]) : 0u;
      if (std::popcount(m) > 1) m = 1u << std::countr_zero(m);
      if (boundary && m == 0) continue;  // should not happen: boundary edges lie on a cut
      const Vec3 p = project(0.5 * (pos_[a] + pos_[b]), m);
      const Index mid = static_cast<Index>(pos_.size());
      pos_.push_back(p);
      mask_.push_back(m);
      valive_.push_back(1);
      vf_.emplace_back();
      for (Index f : ef) {
        Face& F = faces_[f];
        int r = 0;
        while (!((F[r] == a && F[(r + 1) % 3] == b) || (F[r] == b && F[(r + 1) % 3] == a))) ++r;
        const Index x = F[r], y = F[(r + 1) % 3], c = F[(r + 2) % 3];
        F = {x, mid, c};
        const Index nf = static_cast<Index>(faces_.size());
        faces_.push_back({mid, y, c});
        falive_.push_back(1);
        erase_value(vf_[y], f);
        vf_[y].push_back(nf);
        vf_[c].push_back(nf);
        vf_[mid].push_back(f);
        vf_[mid].push_back(nf);
      }
    }
  }

  bool try_collapse(Index a, Index b, double hi) {
    // Removes a, keeps b at its position.
    if (is_corner(a)) return false;
    const auto ef = edge_faces(a, b);
    if (ef.empty()) return false;
    const bool boundary = ef.size() == 1;
    if (mask_[a] != 0) {
      if (!boundary) return false;
      if ((mask_[b] & mask_[a]) != mask_[a]) return false;
    } else if (boundary) {
      return false;
    }
    // Link condition.
    const auto ra = ring(a), rb = ring(b);
    std::vector<Index> common;
    std::set_intersection(ra.begin(), ra.end(), rb.begin(), rb.end(), std::back_inserter(common));
    std::vector<Index> opp;
    for (Index f : ef) opp.push_back(third(faces_[f], a, b));
    std::sort(opp.begin(), opp.end());
    if (common != opp) return false;
    for (Index c : opp) {
      const int minval = mask_[c] ? 3 : 4;
      if (valence(c) < minval) return false;
    }
    if (ra.size() <= 3 && mask_[a] == 0) return false;
    const Vec3 p = pos_[b];
    for (Index n : ra)
      if (n != b && (pos_[n] - p).norm() > hi) return false;
    // No flipped or degenerate faces.
    for (Index f : vf_[a]) {
      const Face& F = faces_[f];
      if (has(F, b)) continue;
      const Vec3 n0 = face_normal_raw(F);
      Face G = F;
      for (int c = 0; c < 3; ++c)
        if (G[c] == a) G[c] = b;
      const Vec3 n1 = (pos_[G[1]] - pos_[G[0]]).cross(pos_[G[2]] - pos_[G[0]]);
      if (n1.norm() < 1e-8) return false;
      if (n0.norm() > 1e-8 && n0.normalized().dot(n1.normalized()) < 0.3) return false;
    }
    // Execute.
    for (Index f : ef) {
      falive_[f] = 0;
      for (int c = 0; c < 3; ++c) erase_value(vf_[faces_[f][c]], f);
    }
    for (Index f : vf_[a]) {
      for (int c = 0; c < 3; ++c)
        if (faces_[f][c] == a) faces_[f][c] = b;
      vf_[b].push_back(f);
    }
    vf_[a].clear();
    valive_[a] = 0;
    return true;
  }

  void collapse_short(double lo, double hi) {
    for (const auto& [a, b] : edges()) {
      if (!valive_[a] || !valive_[b]) continue;
      if ((pos_[a] - pos_[b]).norm() >= lo) continue;
      // Prefer removing the less constrained vertex.
      const int ca = std::popcount(mask_[a]), cb = std::popcount(mask_[b]);
      if (ca <= cb) {
        if (!try_collapse(a, b, hi)) try_collapse(b, a, hi);
      } else {
        if (!try_collapse(b, a, hi)) try_collapse(a, b, hi);
      }
    }
  }

  void flip_valence() {
    for (const auto& [a, b] : edges()) {
      if (!valive_[a] || !valive_[b]) continue;
      const auto ef = edge_faces(a, b);
      if (ef.size() != 2) continue;
      Index f1 = ef[0], f2 = ef[1];
      // Orient so that f1 holds a -> b.
      auto holds = [&](Index f, Index x, Index y) {
        const Face& F = faces_[f];
        for (int r = 0; r < 3; ++r)
          if (F[r] == x && F[(r + 1) % 3] == y) return true;
        return false;
      };
      Index x = a, y = b;
      if (!holds(f1, x, y)) std::swap(f1, f2);
      if (!holds(f1, x, y)) continue;  // inconsistent orientation; leave it
      const Index c = third(faces_[f1], x, y), d = third(faces_[f2], x, y);
      if (c == d) continue;
      if (mask_[c] && mask_[d]) continue;
      const auto rc = ring(c);
      if (std::binary_search(rc.begin(), rc.end(), d)) continue;
      auto target = [&](Index v) { return mask_[v] ? 4 : 6; };
      const int va = valence(x), vb = valence(y), vc = static_cast<int>(rc.size()), vd = valence(d);
      const int before = std::abs(va - target(x)) + std::abs(vb - target(y)) + std::abs(vc - target(c)) +
                         std::abs(vd - target(d));
      const int after = std::abs(va - 1 - target(x)) + std::abs(vb - 1 - target(y)) +
                        std::abs(vc + 1 - target(c)) + std::abs(vd + 1 - target(d));
      if (after >= before) continue;
      if (va - 1 < (mask_[x] ? 2 : 3) || vb - 1 < (mask_[y] ? 2 : 3)) continue;
      // Geometry: new faces (c, x, d) and (c, d, y) must agree with the old ones.
      const Vec3 n_old = (face_normal_raw(faces_[f1]) + face_normal_raw(faces_[f2])).normalized();
      const Vec3 n1 = (pos_[x] - pos_[c]).cross(pos_[d] - pos_[c]);
      const Vec3 n2 = (pos_[d] - pos_[c]).cross(pos_[y] - pos_[c]);
      if (n1.norm() < 1e-8 || n2.norm() < 1e-8) continue;
      if (n1.normalized().dot(n_old) < 0.5 || n2.normalized().dot(n_old) < 0.5) continue;
      faces_[f1] = {c, x, d};
      faces_[f2] = {c, d, y};
      erase_value(vf_[y], f1);
      vf_[d].push_back(f1);
      erase_value(vf_[x], f2);
      vf_[c].push_back(f2);
    }
  }

  void smooth() {
    const size_t nv = pos_.size();
    std::vector<Vec3> next = pos_;
    for (size_t v = 0; v < nv; ++v) {
      if (!valive_[v] || vf_[v].empty() || is_corner(static_cast<Index>(v))) continue;
      if (mask_[v] == 0) {
        // Area-weighted centroid of the incident triangles' centroids.
        Vec3 c = Vec3::Zero();
        double wsum = 0;
        for (Index f : vf_[v]) {
          const Face& F = faces_[f];
          const double area = 0.5 * face_normal_raw(F).norm();
          c += area * (pos_[F[0]] + pos_[F[1]] + pos_[F[2]]) / 3.0;
          wsum += area;
        }
        if (wsum < 1e-12) continue;
        c /= wsum;
        const Vec3 n = field_.normal(pos_[v]);
        Vec3 d = c - pos_[v];
        d -= d.dot(n) * n;
        next[v] = project(pos_[v] + d, 0);
      } else {
        // Average of the two boundary neighbours along the cut.
        Vec3 c = Vec3::Zero();
        int k = 0;
        for (Index n : ring(static_cast<Index>(v))) {
          if (is_boundary_edge(static_cast<Index>(v), n)) {
            c += pos_[n];
            ++k;
          }
        }
        if (k != 2) continue;
        c /= k;
        next[v] = project(0.5 * (pos_[v] + c), mask_[v]);
      }
    }
    pos_.swap(next);
  }

  const BodyField& field_;
  const std::vector<CutPlane>& cuts_;
  std::vector<Vec3> pos_;
  std::vector<std::uint32_t> mask_;
  std::vector<char> valive_;
  std::vector<Face> faces_;
  std::vector<char> falive_;
  std::vector<std::vector<Index>> vf_;
};

}  // namespace

ClippedMesh isotropic_remesh(const ClippedMesh& input, const BodyField& field,
                             const std::vector<CutPlane>& cuts, const RemeshOptions& options) {
  if (!(options.target_edge_mm > 0)) throw InvalidInput("isotropic_remesh: target_edge_mm must be > 0");
  if (options.iterations < 0) throw InvalidInput("isotropic_remesh: iterations must be >= 0");
  if (static_cast<Index>(input.on_cut.size()) != input.mesh.num_vertices())
    throw InvalidInput("isotropic_remesh: on_cut must have one mask per vertex");
  Remesher r(input, field, cuts);
  r.run(options);
  return r.result();
}

}  // namespace breastfit::templ
