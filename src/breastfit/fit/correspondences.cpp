#include "breastfit/fit/correspondences.h"

#include <cmath>
#include <utility>

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

std::vector<Correspondence> find_correspondences(const Points& V, const Points& N, const ScanTarget& scan,
                                                 const CorrespondenceOptions& o, double max_distance_mm,
                                                 int stride, CorrespondenceStats* stats, std::vector<Index>* hints) {
  if (hints && static_cast<Index>(hints->size()) != V.rows()) hints->assign(V.rows(), -1);
  const double cos_limit = std::cos(o.max_normal_angle_deg * M_PI / 180.0);
  CorrespondenceStats st;
  st.max_distance_mm = max_distance_mm;
  std::vector<Correspondence> out;
  out.reserve(V.rows() / stride + 1);
  for (Index i = 0; i < V.rows(); i += stride) {
    ++st.candidates;
    const Vec3 q = V.row(i).transpose();
    const auto m = scan.match(q, max_distance_mm, hints ? &(*hints)[i] : nullptr);
    if (!m) {
      ++st.rejected_distance;
      continue;
    }
    if (o.reject_boundary && m->on_boundary) {
      ++st.rejected_boundary;
      continue;
    }
    const Vec3 n = N.row(i).transpose();
    if (n.dot(m->normal) < cos_limit) {
      ++st.rejected_normal;
      continue;
    }
    Correspondence c;
    c.vertex = i;
    c.target = m->point;
    c.normal = m->normal;
    const double r = std::sqrt((1.0 - o.point_to_point_weight) * std::pow(c.normal.dot(q - c.target), 2) +
                               o.point_to_point_weight * (q - c.target).squaredNorm());
    c.weight = robust_weight(o.kernel, r, o.kernel_scale_mm);
    out.push_back(c);
    ++st.kept;
  }
  if (stats) *stats = st;
  return out;
}

std::vector<ReverseCorrespondence> find_reverse_correspondences(const Points& V, const Triangles& F,
                                                                const ScanTarget& scan,
                                                                const CorrespondenceOptions& o,
                                                                double max_distance_mm,
                                                                CorrespondenceStats* stats,
                                                                std::vector<Index>* hints) {
  const double cos_limit = std::cos(o.max_normal_angle_deg * M_PI / 180.0);
  TriangleMesh posed;
  posed.V = V;
  posed.F = F;
  const spatial::ClosestPointIndex index(std::move(posed));
  const Points& S = scan.sample_points();
  const Points SN = scan.sample_normals();
  if (hints && static_cast<Index>(hints->size()) != S.rows()) hints->assign(S.rows(), -1);
  CorrespondenceStats st;
  st.max_distance_mm = max_distance_mm;
  std::vector<ReverseCorrespondence> out;
  out.reserve(S.rows());
  for (Index s = 0; s < S.rows(); ++s) {
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
  if (stats) *stats = st;
  return out;
}

}  // namespace breastfit::fit
