#include "breastfit/fit/scan_target.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "breastfit/core/errors.h"
#include "breastfit/core/rng.h"
#include "breastfit/fit/parallel_chunks.h"
#include "breastfit/fit/skin_around.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/spatial/closest_point_index.h"

namespace breastfit::fit {

struct ScanTarget::Skin {
  std::once_flag once;
  std::vector<char> labels;
};

ScanTarget::ScanTarget(const TriangleMesh& scan_mm, int num_samples, int threads) : skin_(std::make_unique<Skin>()) {
  if (scan_mm.num_faces() == 0) throw InvalidInput("the scan has no triangles");
  index_ = std::make_unique<spatial::ClosestPointIndex>(scan_mm, resolve_threads(threads));
  const TriangleMesh& mesh = index_->mesh();
  // Area-uniform deterministic samples.
  const Index nf = mesh.num_faces();
  std::vector<double> cumulative(nf, 0.0);
  const Eigen::VectorXd area = mesh::face_areas(mesh);
  double total = 0.0;
  for (Index f = 0; f < nf; ++f) {
    total += area[f];
    cumulative[f] = total;
  }
  if (num_samples > 0 && total > 0) {
    Rng rng(12345);
    samples_.resize(num_samples, 3);
    sample_normals_.resize(num_samples, 3);
    for (int s = 0; s < num_samples; ++s) {
      const double u = rng.uniform() * total;
      const Index f = static_cast<Index>(std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin());
      const Index ff = std::min<Index>(f, nf - 1);
      double r1 = rng.uniform(), r2 = rng.uniform();
      if (r1 + r2 > 1) { r1 = 1 - r1; r2 = 1 - r2; }
      const Vec3 a = mesh.V.row(mesh.F(ff, 0));
      const Vec3 b = mesh.V.row(mesh.F(ff, 1));
      const Vec3 c = mesh.V.row(mesh.F(ff, 2));
      samples_.row(s) = (a + r1 * (b - a) + r2 * (c - a)).transpose();
      sample_normals_.row(s) = index_->face_normal(ff).transpose();
    }
  }
}

ScanTarget::~ScanTarget() = default;
ScanTarget::ScanTarget(ScanTarget&&) noexcept = default;

const TriangleMesh& ScanTarget::mesh() const { return index_->mesh(); }

const Points& ScanTarget::vertex_normals() const { return index_->vertex_normals(); }

const std::vector<char>& ScanTarget::skin() const {
  std::call_once(skin_->once, [this] { skin_->labels = skin_vertices(mesh()); });
  return skin_->labels;
}

Points ScanTarget::sample_normals() const { return normal_sign_ * sample_normals_; }

std::optional<ScanMatch> ScanTarget::match(const Vec3& q, double max_dist, Index* hint_face) const {
  auto cp = hint_face && *hint_face >= 0 ? index_->closest_within(q, max_dist, *hint_face)
                                         : index_->closest_within(q, max_dist);
  if (!cp) return std::nullopt;
  if (hint_face) *hint_face = cp->face;
  ScanMatch m;
  m.face = cp->face;
  m.point = cp->point;
  m.normal = normal_sign_ * index_->smooth_normal(*cp);
  m.sq_dist = cp->sq_dist;
  m.on_boundary = cp->on_boundary;
  return m;
}

ScanMatch ScanTarget::closest(const Vec3& q, Index* hint_face) const {
  const auto cp = hint_face && *hint_face >= 0 ? index_->closest(q, *hint_face) : index_->closest(q);
  if (hint_face) *hint_face = cp.face;
  ScanMatch m;
  m.face = cp.face;
  m.point = cp.point;
  m.normal = normal_sign_ * index_->smooth_normal(cp);
  m.sq_dist = cp.sq_dist;
  m.on_boundary = cp.on_boundary;
  return m;
}

}  // namespace breastfit::fit
