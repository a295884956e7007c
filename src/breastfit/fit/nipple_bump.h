#pragma once
/// \file The nipple found on the scan as its own bump: the nipple–areola complex stands a few
/// millimetres above the breast's skin around it.
///
/// Bump height of a scan vertex: the mean height of the scan within `disc_mm` (3 mm) of it above
/// the plane fitted to the scan's ring `ring_inner_mm`–`ring_outer_mm` (8–16 mm) from it, its
/// normal turned to the scan's outward normal there. On the breast the curvature alone gives
/// 1–2 mm (the median); the nipple's bump peaks at 4–8 mm on the benchmark and validation scans,
/// and the centroid of the vertices within `peak_cap_mm` (0.3 mm) of the peak is the bump.
///
/// The scans are dense (3–4 vertices per mm² on the breast), so the vertices measured within
/// `search_radius_mm` of the centre are one per `ring_cell_mm` (4 mm) cell, the rings' planes are
/// fitted to those cells' vertices and the discs averaged over one vertex per `disc_cell_mm`
/// (1.5 mm) cell; the peak is then refined over the fine cells within 4 mm of the highest coarse
/// one. The scan around the centre comes from the fit's own index of the scan
/// (ClosestPointIndex::vertices_within; a pass over every vertex without one), and the rings and
/// discs from grids of cells as wide as their radii over the few hundred coarse and few thousand
/// fine vertices: no second tree over the scan (about a millisecond per nipple, session 16).
///
/// The bump is *refused* (nullopt) unless the peak is distinct and single: at least `min_peak_mm`
/// (3 mm) high, at most `max_peak_mm` (9 mm; higher is a scan artefact), at least
/// `min_peak_over_median` (2) times the median, and every vertex farther than `single_radius_mm`
/// (8 mm) from the bump at most `max_second_ratio` (0.8) of its height. The template-made
/// synthetic torsos have no areola (peaks 2.3–3.3 mm, second peaks at 0.86–0.95 of them): the
/// detector refuses there and the breast's tip and apex checks stand alone. Measured in
/// docs/REGISTRATION.md, sessions 14 and 15.
#include <optional>

#include "breastfit/core/types.h"

namespace breastfit::spatial {
class ClosestPointIndex;
}

namespace breastfit::fit {

struct NippleBumpOptions {
  double search_radius_mm = 35.0;  ///< scan vertices this close to the centre are measured
  double ring_cell_mm = 4.0;       ///< one scan vertex per cell this wide: the vertices measured and the rings' points
  double disc_cell_mm = 1.5;       ///< one per cell this wide: the discs' points (the scans are dense)
  double disc_mm = 3.0;            ///< the vertex's height: mean over the scan this close to it
  double ring_inner_mm = 8.0;      ///< the reference plane: fitted to the scan this far …
  double ring_outer_mm = 16.0;     ///< … to this far from the vertex
  double peak_cap_mm = 0.3;        ///< the bump: centroid of the vertices this close to the peak height
  double min_peak_mm = 3.0;
  double max_peak_mm = 9.0;
  double min_peak_over_median = 2.0;
  double single_radius_mm = 8.0;   ///< a second peak farther than this from the bump …
  double max_second_ratio = 0.8;   ///< … higher than this fraction of the peak: refused
};

/// A bump found on the scan.
struct NippleBump {
  Vec3 position = Vec3::Zero();  ///< centroid of the vertices within peak_cap_mm of the peak height
  double peak_mm = 0;            ///< highest bump height
  double median_mm = 0;          ///< median bump height of the vertices measured
  double second_mm = 0;          ///< highest bump height farther than single_radius_mm from the bump
};

/// The bump around `centre` as measured, before the distinctness test (is_distinct_bump); nullopt
/// when fewer than 3 vertices could be measured.
std::optional<NippleBump> measure_nipple_bump(const Points& scan_vertices, const Points& scan_normals,
                                              const Vec3& centre, const NippleBumpOptions& options = {});

/// The same measurement around `centre` over the vertices of an indexed scan (those of its
/// triangles: a vertex no triangle uses is left out), found through the index instead of a pass
/// over every vertex. The same bits as the overload above on a scan whose vertices are all used.
/// \param scan_normals the scan's outward unit vertex normals (rows as scan.mesh().V)
std::optional<NippleBump> measure_nipple_bump(const spatial::ClosestPointIndex& scan, const Points& scan_normals,
                                              const Vec3& centre, const NippleBumpOptions& options = {});

/// Whether a measured bump is a distinct, single peak (the rules of the file comment).
bool is_distinct_bump(const NippleBump& bump, const NippleBumpOptions& options = {});

/// The nipple's bump on the scan near `centre`: measure_nipple_bump when is_distinct_bump, else
/// nullopt. \param scan_normals the scan's outward unit vertex normals
std::optional<NippleBump> nipple_bump_on_scan(const Points& scan_vertices, const Points& scan_normals,
                                              const Vec3& centre, const NippleBumpOptions& options = {});
/// nipple_bump_on_scan over an indexed scan (the fit's: ScanTarget::index()).
std::optional<NippleBump> nipple_bump_on_scan(const spatial::ClosestPointIndex& scan, const Points& scan_normals,
                                              const Vec3& centre, const NippleBumpOptions& options = {});

}  // namespace breastfit::fit
