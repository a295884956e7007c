#include "breastfit/mesh/units.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "breastfit/core/errors.h"

namespace breastfit::mesh {

double max_extent(const Points& P) {
  if (P.rows() == 0) return 0.0;
  return (P.colwise().maxCoeff() - P.colwise().minCoeff()).maxCoeff();
}

Units detect_units(const Points& P) {
  if (P.rows() == 0) throw InvalidInput("cannot detect the units of an empty point set; pass --units");
  if (!P.allFinite()) throw InvalidInput("cannot detect units: the points contain NaN or Inf");
  const double extent = max_extent(P);
  if (!(extent > 0.0))
    throw InvalidInput("cannot detect the units of points with zero extent; pass --units");
  if (extent < 5.0) return Units::Metres;
  if (extent >= 50.0 && extent <= 5000.0) return Units::Millimetres;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", extent);
  throw InvalidInput(std::string("extent ") + buf +
                     " units is neither a torso in mm nor in m; pass --units");
}

double to_mm_factor(Units units) { return units == Units::Metres ? 1000.0 : 1.0; }

std::string_view units_name(Units units) { return units == Units::Metres ? "m" : "mm"; }

std::optional<Units> parse_units(std::string_view text) {
  if (text == "mm") return Units::Millimetres;
  if (text == "m") return Units::Metres;
  if (text == "auto") return std::nullopt;
  throw InvalidInput("units '" + std::string(text) + "' is not one of auto, mm, m");
}

Units resolve_units(std::optional<Units> requested, const Points& P) {
  return requested ? *requested : detect_units(P);
}

}  // namespace breastfit::mesh
