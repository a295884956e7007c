#include "breastfit/fit/nipple_bump.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "breastfit/spatial/cell_grid.h"
#include "breastfit/spatial/closest_point_index.h"

namespace breastfit::fit {

namespace {

// One scan vertex per cell of a `cell_mm` grid, among `points` (indices into them): the first of
// each cell, ascending. The cells seen are kept in an open-addressing set of their keys (a few
// thousand points per call, twice per nipple: std::unordered_map's node per cell cost more than
// the rest of the pass).
std::vector<Index> one_per_cell(const Points& points, double cell_mm) {
  size_t slots = 16;
  while (slots < 2 * static_cast<size_t>(points.rows())) slots *= 2;
  constexpr std::int64_t kEmpty = -1;  // keys are 63-bit: never negative
  std::vector<std::int64_t> seen(slots, kEmpty);
  std::vector<Index> out;
  for (Index i = 0; i < points.rows(); ++i) {
    const auto c = [&](int axis) { return static_cast<std::int64_t>(std::floor(points(i, axis) / cell_mm)) & 0x1fffff; };
    const std::int64_t key = (c(0) << 42) | (c(1) << 21) | c(2);
    size_t slot = static_cast<size_t>((static_cast<std::uint64_t>(key) * 0x9E3779B97F4A7C15ULL) >> 20) & (slots - 1);
    while (seen[slot] != kEmpty && seen[slot] != key) slot = (slot + 1) & (slots - 1);
    if (seen[slot] == key) continue;
    seen[slot] = key;
    out.push_back(i);
  }
  return out;
}

Points rows_of(const Points& points, const std::vector<Index>& rows) {
  Points out(static_cast<Index>(rows.size()), 3);
  for (size_t k = 0; k < rows.size(); ++k) out.row(static_cast<Index>(k)) = points.row(rows[k]);
  return out;
}

// The measurement over the scan vertices `local` (ascending indices): those within the search
// radius and the ring's outer radius of the centre.
std::optional<NippleBump> measure_local(const Points& scan_vertices, const Points& scan_normals,
                                        const std::vector<Index>& local, const Vec3& centre,
                                        const NippleBumpOptions& options) {
  // The scans are dense (3–4 vertices per mm² on the breast): the reference planes are fitted to
  // one vertex per ring_cell_mm cell, the heights averaged over one per disc_cell_mm cell, and the
  // vertices measured are the coarse cells' within the search radius, then every fine one within
  // coarse_cell_mm of the highest.
  if (local.size() < 3) return std::nullopt;
  const Points L = rows_of(scan_vertices, local);
  const std::vector<Index> coarse_rows = one_per_cell(L, options.ring_cell_mm),
                           fine_rows = one_per_cell(L, options.disc_cell_mm);
  const Points coarse = rows_of(L, coarse_rows), fine = rows_of(L, fine_rows);
  // Rings in cells of half their radius (a quarter of the volume read), discs in cells of theirs.
  const spatial::CellGrid coarse_cells(coarse, options.ring_outer_mm, 2), fine_cells(fine, options.disc_mm, 1);

  const double inner2 = options.ring_inner_mm * options.ring_inner_mm;
  std::vector<Index> nb;
  std::vector<double> sq;
  // The bump height at p (scan normal n_p), or nullopt without enough scan around it.
  const auto height_at = [&](const Vec3& p, const Vec3& n_p) -> std::optional<double> {
    // The ring only (sorted without the disc inside it): the ring's points in the ball's order.
    coarse_cells.within(p, options.ring_outer_mm, nb, sq, inner2);
    Vec3 sum = Vec3::Zero();
    int n = 0;
    for (const Index j : nb) {
      sum += coarse.row(j).transpose();
      ++n;
    }
    if (n < 6) return std::nullopt;
    const Vec3 c = sum / n;
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Index j : nb) {
      const Vec3 d = coarse.row(j).transpose() - c;
      cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(cov);
    Vec3 normal = eig.eigenvectors().col(0);
    if (normal.dot(n_p) < 0) normal = -normal;
    fine_cells.within(p, options.disc_mm, nb, sq);
    if (nb.empty()) return std::nullopt;
    double h = 0;
    for (Index j : nb) h += (fine.row(j).transpose() - c).dot(normal);
    return h / static_cast<double>(nb.size());
  };

  const double search2 = options.search_radius_mm * options.search_radius_mm;
  std::vector<Vec3> where;
  std::vector<double> height;
  for (size_t k = 0; k < coarse_rows.size(); ++k) {
    const Vec3 p = coarse.row(static_cast<Index>(k)).transpose();
    if ((p - centre).squaredNorm() > search2) continue;
    if (const auto h = height_at(p, scan_normals.row(local[coarse_rows[k]]).transpose())) {
      where.push_back(p);
      height.push_back(*h);
    }
  }
  if (height.size() < 3) return std::nullopt;
  std::vector<double> sorted = height;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
  const double median = sorted[sorted.size() / 2];
  const size_t top = static_cast<size_t>(std::max_element(height.begin(), height.end()) - height.begin());
  const Vec3 coarse_peak = where[top];
  const size_t n_coarse = height.size();
  // The peak at the fine cells' resolution.
  const double refine2 = options.ring_cell_mm * options.ring_cell_mm;
  for (size_t k = 0; k < fine_rows.size(); ++k) {
    const Vec3 p = fine.row(static_cast<Index>(k)).transpose();
    if ((p - coarse_peak).squaredNorm() > refine2 || (p - centre).squaredNorm() > search2) continue;
    if (const auto h = height_at(p, scan_normals.row(local[fine_rows[k]]).transpose())) {
      where.push_back(p);
      height.push_back(*h);
    }
  }

  NippleBump bump;
  bump.median_mm = median;
  bump.peak_mm = *std::max_element(height.begin(), height.end());
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (size_t k = 0; k < height.size(); ++k)
    if (height[k] >= bump.peak_mm - options.peak_cap_mm) {
      sum += where[k];
      ++n;
    }
  bump.position = sum / n;
  for (size_t k = 0; k < n_coarse; ++k)
    if ((where[k] - bump.position).norm() > options.single_radius_mm) bump.second_mm = std::max(bump.second_mm, height[k]);
  return bump;
}

}  // namespace

std::optional<NippleBump> measure_nipple_bump(const Points& scan_vertices, const Points& scan_normals,
                                              const Vec3& centre, const NippleBumpOptions& options) {
  const double reach = options.search_radius_mm + options.ring_outer_mm;
  std::vector<Index> local;
  for (Index i = 0; i < scan_vertices.rows(); ++i)
    if (spatial::row_sq_dist(scan_vertices, i, centre) <= reach * reach) local.push_back(i);
  return measure_local(scan_vertices, scan_normals, local, centre, options);
}

std::optional<NippleBump> measure_nipple_bump(const spatial::ClosestPointIndex& scan, const Points& scan_normals,
                                              const Vec3& centre, const NippleBumpOptions& options) {
  std::vector<Index> local;
  scan.vertices_within(centre, options.search_radius_mm + options.ring_outer_mm, local);
  return measure_local(scan.mesh().V, scan_normals, local, centre, options);
}

bool is_distinct_bump(const NippleBump& bump, const NippleBumpOptions& options) {
  return bump.peak_mm >= options.min_peak_mm && bump.peak_mm <= options.max_peak_mm &&
         bump.peak_mm >= options.min_peak_over_median * bump.median_mm &&
         bump.second_mm <= options.max_second_ratio * bump.peak_mm;
}

std::optional<NippleBump> nipple_bump_on_scan(const Points& scan_vertices, const Points& scan_normals,
                                              const Vec3& centre, const NippleBumpOptions& options) {
  auto bump = measure_nipple_bump(scan_vertices, scan_normals, centre, options);
  if (!bump || !is_distinct_bump(*bump, options)) return std::nullopt;
  return bump;
}

std::optional<NippleBump> nipple_bump_on_scan(const spatial::ClosestPointIndex& scan, const Points& scan_normals,
                                              const Vec3& centre, const NippleBumpOptions& options) {
  auto bump = measure_nipple_bump(scan, scan_normals, centre, options);
  if (!bump || !is_distinct_bump(*bump, options)) return std::nullopt;
  return bump;
}

}  // namespace breastfit::fit
