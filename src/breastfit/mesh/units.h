#pragma once
/// \file Length units of input files (scanners export millimetres or metres) and their detection.
///
/// Inside the library every length is in millimetres; files keep their own units. A torso spans
/// about 250-700 mm, so the largest bounding-box extent tells the units apart:
///   extent < 5            -> metres
///   5 <= extent < 50      -> ambiguous (neither a torso in mm nor in m): error
///   50 <= extent <= 5000  -> millimetres
///   extent > 5000         -> ambiguous: error
#include <optional>
#include <string_view>

#include "breastfit/core/types.h"

namespace breastfit::mesh {

enum class Units { Millimetres, Metres };

/// Largest extent of the axis-aligned bounding box of the points, in their units (0 when empty).
double max_extent(const Points& P);

/// Guesses the units of a torso-sized point set from its largest bounding-box extent (see the
/// file comment for the thresholds).
/// \param[in] P  #P by 3 positions in file units
/// \throws InvalidInput "extent X units is neither a torso in mm nor in m; pass --units" when the
///         extent is ambiguous, or when P is empty, of zero extent or not finite
Units detect_units(const Points& P);

/// Multiply a length in `units` by this to get millimetres (1 or 1000).
double to_mm_factor(Units units);

/// "mm" or "m".
std::string_view units_name(Units units);

/// Parses a units choice: "mm" -> Millimetres, "m" -> Metres, "auto" -> nullopt (detect).
/// \throws InvalidInput for any other text, listing the accepted values
std::optional<Units> parse_units(std::string_view text);

/// The units to use: `requested` when given, otherwise detect_units(P).
/// \throws InvalidInput as detect_units
Units resolve_units(std::optional<Units> requested, const Points& P);

}  // namespace breastfit::mesh
