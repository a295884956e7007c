#include "breastfit/fit/correspondences.h"

#include <cmath>
#include <utility>

#include "breastfit/fit/parallel_chunks.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/spatial/closest_point_index.h"

namespace breastfit::fit {

double robust_weight(RobustKernel kernel, double r, double sigma) {
  const double a = std::abs(r);
  switch (kernel) {
    case RobustKernel::None: return 1.0;
    case RobustKernel::Huber: return a <= sigma ? 1.0 : sigma / a;
    case RobustKernel::GemanMcClure: {
      const double s2 = sigma * sigma;
      const double d = s2 + r * r;
      return (s2 * s2) / (d * d);
    }
  }
  return 1.0;
}

namespace {

// Queries per chunk of the parallel searches (fixed: the output does not depend on the threads).
constexpr Index kQueryChunk = 64;
// How many queries ahead find_correspondences fetches its hints' triangles (see there).
constexpr Index kPrefetchAhead = 4;

// One chunk's pairs and counts; chunks are concatenated and summed in chunk order.
template <class Pair>
struct ChunkResult {
  std::vector<Pair> pairs;
  CorrespondenceStats stats;
};

template <class Pair>
std::vector<Pair> concatenate(std::vector<ChunkResult<Pair>>& chunks, double max_distance_mm,
                              CorrespondenceStats* stats) {
  CorrespondenceStats st;
  st.max_distance_mm = max_distance_mm;
  size_t total = 0;
  for (const auto& c : chunks) total += c.pairs.size();
  std::vector<Pair> out;
  out.reserve(total);
  for (auto& c : chunks) {
    out.insert(out.end(), c.pairs.begin(), c.pairs.end());
    st.candidates += c.stats.candidates;
    st.kept += c.stats.kept;
    st.rejected_distance += c.stats.rejected_distance;
    st.rejected_boundary += c.stats.rejected_boundary;
    st.rejected_normal += c.stats.rejected_normal;
  }
  if (stats) *stats = st;
  return out;
}

}  // namespace

std::vector<Correspondence> find_correspondences(const Points& V, const Points& N, const ScanTarget& scan,
                                                 const CorrespondenceOptions& o, double max_distance_mm,
                                                 int stride, CorrespondenceStats* stats, std::vector<Index>* hints,
                                                 int threads) {
  if (hints && static_cast<Index>(hints->size()) != V.rows()) hints->assign(V.rows(), -1);
  const double cos_limit = std::cos(o.max_normal_angle_deg * M_PI / 180.0);
  const Index candidates = V.rows() > 0 ? (V.rows() - 1) / stride + 1 : 0;  // vertices 0, stride, 2·stride, …
  // The searches run along a Morton curve over the candidates (nearby queries one after another
  // find the scan index's nodes in the cache), each candidate's outcome in its own slot; the pairs
  // are then gathered in vertex order (the same pairs and counts as searching in vertex order).
  Points Q(candidates, 3);
  for (Index k = 0; k < candidates; ++k) Q.row(k) = V.row(k * stride);
  const std::vector<std::uint32_t> order = spatial::query_order(Q);
  enum class Outcome : std::uint8_t { Kept, Distance, Boundary, Normal };
  std::vector<Outcome> outcome(static_cast<size_t>(candidates));
  std::vector<Correspondence> found(static_cast<size_t>(candidates));
  // Each search starts from its hint's triangle and ends reading the found one's corners and
  // their normals (mostly the hint's): on a large scan these are cache misses one after another.
  // They are fetched a few queries ahead — the triangle's corner indices kPrefetchAhead queries
  // ahead, its corners and their normals half as far (the indices are there by then). Only the
  // speed depends on it.
  const Points& SV = scan.mesh().V;
  const Triangles& SF = scan.mesh().F;
  const Points& SN = scan.vertex_normals();
  const auto hint_of = [&](Index j) -> Index {
    const Index h = (*hints)[static_cast<size_t>(order[static_cast<size_t>(j)]) * static_cast<size_t>(stride)];
    return h >= 0 && h < SF.rows() ? h : -1;
  };
  for_each_chunk(candidates, kQueryChunk, threads, [&](Index, Index begin, Index end) {
    for (Index j = begin; j < end; ++j) {
      if (hints) {
        if (j + kPrefetchAhead < end)
          if (const Index h = hint_of(j + kPrefetchAhead); h >= 0) __builtin_prefetch(SF.data() + 3 * h);
        if (j + kPrefetchAhead / 2 < end)
          if (const Index h = hint_of(j + kPrefetchAhead / 2); h >= 0)
            for (int c = 0; c < 3; ++c) {
              __builtin_prefetch(SV.data() + 3 * static_cast<std::ptrdiff_t>(SF(h, c)));
              __builtin_prefetch(SN.data() + 3 * static_cast<std::ptrdiff_t>(SF(h, c)));
            }
      }
      const Index k = static_cast<Index>(order[static_cast<size_t>(j)]);
      const Index i = k * stride;
      Outcome& out = outcome[static_cast<size_t>(k)];
      const Vec3 q = Q.row(k).transpose();
      const auto m = scan.match(q, max_distance_mm, hints ? &(*hints)[i] : nullptr);
      if (!m) {
        out = Outcome::Distance;
        continue;
      }
      if (o.reject_boundary && m->on_boundary) {
        out = Outcome::Boundary;
        continue;
      }
      const Vec3 n = N.row(i).transpose();
      if (n.dot(m->normal) < cos_limit) {
        out = Outcome::Normal;
        continue;
      }
      Correspondence& c = found[static_cast<size_t>(k)];
      c.vertex = i;
      c.target = m->point;
      c.normal = m->normal;
      const double r = std::sqrt((1.0 - o.point_to_point_weight) * std::pow(c.normal.dot(q - c.target), 2) +
                                 o.point_to_point_weight * (q - c.target).squaredNorm());
      c.weight = robust_weight(o.kernel, r, o.kernel_scale_mm);
      out = Outcome::Kept;
    }
  });
  CorrespondenceStats st;
  st.max_distance_mm = max_distance_mm;
  st.candidates = static_cast<int>(candidates);
  std::vector<Correspondence> pairs;
  pairs.reserve(static_cast<size_t>(candidates));
  for (Index k = 0; k < candidates; ++k) {
    switch (outcome[static_cast<size_t>(k)]) {
      case Outcome::Kept:
        pairs.push_back(found[static_cast<size_t>(k)]);
        ++st.kept;
        break;
      case Outcome::Distance: ++st.rejected_distance; break;
      case Outcome::Boundary: ++st.rejected_boundary; break;
      case Outcome::Normal: ++st.rejected_normal; break;
    }
  }
  if (stats) *stats = st;
  return pairs;
}

std::vector<ReverseCorrespondence> find_reverse_correspondences(const spatial::ClosestPointIndex& index,
                                                                const ScanTarget& scan,
                                                                const CorrespondenceOptions& o,
                                                                double max_distance_mm,
                                                                CorrespondenceStats* stats,
                                                                std::vector<Index>* hints, int threads) {
  const double cos_limit = std::cos(o.max_normal_angle_deg * M_PI / 180.0);
  const Points& S = scan.sample_points();
  const Points SN = scan.sample_normals();
  if (hints && static_cast<Index>(hints->size()) != S.rows()) hints->assign(S.rows(), -1);
  std::vector<ChunkResult<ReverseCorrespondence>> chunks(static_cast<size_t>(num_chunks(S.rows(), kQueryChunk)));
  for_each_chunk(S.rows(), kQueryChunk, threads, [&](Index chunk, Index begin, Index end) {
    auto& out = chunks[static_cast<size_t>(chunk)].pairs;
    CorrespondenceStats& st = chunks[static_cast<size_t>(chunk)].stats;
    out.reserve(static_cast<size_t>(end - begin));
    for (Index s = begin; s < end; ++s) {
      ++st.candidates;
      const Vec3 p = S.row(s).transpose();
      Index* hint = hints ? &(*hints)[s] : nullptr;
      const auto cp = hint && *hint >= 0 ? index.closest_within(p, max_distance_mm, *hint)
                                         : index.closest_within(p, max_distance_mm);
      if (cp && hint) *hint = cp->face;
      if (!cp) {
        ++st.rejected_distance;
        continue;
      }
      if (cp->on_boundary) {
        ++st.rejected_boundary;
        continue;
      }
      const Vec3 n = SN.row(s).transpose();
      if (index.smooth_normal(*cp).dot(n) < cos_limit) {
        ++st.rejected_normal;
        continue;
      }
      ReverseCorrespondence c;
      c.source = p;
      c.normal = n;
      c.model_point.face = cp->face;
      c.model_point.bary = cp->bary;
      const double r = std::abs(n.dot(cp->point - p));
      c.weight = robust_weight(o.kernel, r, o.kernel_scale_mm);
      out.push_back(c);
      ++st.kept;
    }
  });
  return concatenate(chunks, max_distance_mm, stats);
}

}  // namespace breastfit::fit
