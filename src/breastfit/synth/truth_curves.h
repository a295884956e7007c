#pragma once
/// \file Dense truth curves: a polyline through points on a surface, densified, projected onto
/// the surface and resampled at a fixed arc-length spacing (bench: ~1 mm).
#include "breastfit/core/types.h"
#include "breastfit/spatial/closest_point_index.h"

namespace breastfit::synth {

/// Resamples the polyline P (#P by 3, on or near the surface) every `spacing_mm` of arc length,
/// every output point being the closest point of the surface to the resampled position (so the
/// points lie exactly on the surface). Starts at P's first point; an open curve keeps both ends,
/// a closed one does not repeat the first point.
/// \param[in] P         #P by 3 (>= 2 points)
/// \param[in] closed    whether the last point joins the first
/// \param[in] surface   closest-point index of the surface
/// \param[in] spacing_mm  > 0
/// \throws InvalidInput for fewer than 2 points or a non-positive spacing
Points resample_on_surface(const Points& P, bool closed, const spatial::ClosestPointIndex& surface,
                           double spacing_mm);

}  // namespace breastfit::synth
