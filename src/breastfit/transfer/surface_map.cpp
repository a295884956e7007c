#include "breastfit/transfer/surface_map.h"

#include <cmath>
#include <optional>
#include <string>

#include "breastfit/core/errors.h"

namespace breastfit::transfer {
namespace {

TriangleMesh checked_to(const TriangleMesh& from, const TriangleMesh& to) {
  if (from.num_faces() == 0 || to.num_faces() == 0) throw InvalidInput("SurfaceMap: a fitted mesh has no triangles");
  if (from.num_vertices() != to.num_vertices() || from.F != to.F)
    throw InvalidInput("SurfaceMap: the two fits are not posings of the same template (" +
                       std::to_string(from.num_vertices()) + " vs " + std::to_string(to.num_vertices()) + " vertices)");
  TriangleMesh out;
  out.V = to.V;
  out.F = to.F;
  return out;
}

}  // namespace

SurfaceMap::SurfaceMap(const TriangleMesh& from_mm, const TriangleMesh& to_mm)
    : from_index_(from_mm), to_(checked_to(from_mm, to_mm)) {}

SurfaceMap::~SurfaceMap() = default;

SurfaceMap::Mapped SurfaceMap::map(const Vec3& q) const {
  if (!q.allFinite()) throw InvalidInput("SurfaceMap::map: non-finite point");
  const auto cp = from_index_.closest(q);
  Mapped m;
  m.surface.face = cp.face;
  m.surface.bary = cp.bary;
  m.on_from = cp.point;
  m.on_to = m.surface.position(to_.V, to_.F);
  m.distance_from_mm = std::sqrt(cp.sq_dist);
  return m;
}

void MapOptions::validate() const {
  if (!(high_confidence_mm >= 0) || !std::isfinite(high_confidence_mm))
    throw InvalidInput("MapOptions.high_confidence_mm must be >= 0");
  if (!(medium_confidence_mm >= high_confidence_mm) || !std::isfinite(medium_confidence_mm))
    throw InvalidInput("MapOptions.medium_confidence_mm must be >= high_confidence_mm");
  projection.validate();
}

int MapResult::count(const std::string& confidence) const {
  int n = 0;
  for (const auto& p : points) n += p.confidence == confidence;
  return n;
}

MapResult map_markups(const Markups& input, const TriangleMesh& fit_a_mm, const TriangleMesh& fit_b_mm,
                      const fit::ScanTarget* scan_b, const MapOptions& options) {
  options.validate();
  const SurfaceMap map(fit_a_mm, fit_b_mm);
  std::optional<DrawingTransfer> onto;
  if (scan_b) onto.emplace(*scan_b, map.to(), options.projection);
  MapResult r;
  auto one = [&](const std::string& markup, const std::string& label, const Vec3& q) {
    const SurfaceMap::Mapped m = map.map(q);
    MappedPoint p;
    p.markup = markup;
    p.label = label;
    p.input = q;
    p.output = m.on_to;
    p.distance_to_fit_a_mm = m.distance_from_mm;
    if (onto) {
      const auto proj = onto->project_point(m.on_to);
      p.projected = true;
      p.supported_by_scan_b = proj.supported;
      p.scan_b_offset_mm = proj.model_to_scan_mm;
      p.output = proj.point;
    }
    const bool ok = !p.projected || p.supported_by_scan_b;
    p.confidence = ok && p.distance_to_fit_a_mm <= options.high_confidence_mm     ? "high"
                   : ok && p.distance_to_fit_a_mm <= options.medium_confidence_mm ? "medium"
                                                                                  : "low";
    r.points.push_back(p);
    return p.output;
  };
  for (const auto& np : input.points) r.markups.points.push_back({np.name, one("points", np.name, np.position)});
  for (const auto& c : input.curves) {
    Curve out{c.name, c.closed, Points(c.points.rows(), 3)};
    for (Eigen::Index i = 0; i < c.points.rows(); ++i)
      out.points.row(i) = one(c.name, std::to_string(i), c.points.row(i).transpose()).transpose();
    r.markups.curves.push_back(std::move(out));
  }
  return r;
}

}  // namespace breastfit::transfer
