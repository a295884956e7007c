#pragma once
/// \file 3D Slicer Markups JSON (`.mrk.json`, schema markups-schema-v1.0.3): landmarks in,
/// landmarks and drawings out.
///
/// Reading accepts any number of markups: "Fiducial" point lists (each control point's `label`
/// is the point's name), "Curve", "ClosedCurve" and "Line" (the markup's `name` is the curve's
/// name; a Line is an open curve of its two points); other markup types (Angle, Plane, ROI, ...)
/// are skipped with a warning naming them (MarkupsFile::warnings). `coordinateSystem` "LPS" (the
/// default when absent) or "RAS" (converted to LPS by negating x and y); `coordinateUnits` "mm"
/// (the default when absent) or "m", as a string or as a coded array such as
/// ["m", "UCUM", "meter"]. Control points whose `positionStatus` is "missing", "undefined" or
/// "preview" (skipped, never placed or still being placed in Slicer; their `position` may be ""
/// or absent) are left out with a warning naming them (the rest of the file is kept); any other
/// control point must have a finite 3-vector
/// `position`. Bare NaN / Infinity tokens (as Python's json module writes them) are reported as
/// non-finite coordinates of the point they belong to, not as malformed JSON.
///
/// Example:
/// \code
///   breastfit::Markups in = breastfit::io::read_markups("landmarks.mrk.json");   // LPS mm
///   breastfit::io::write_markups("drawings.mrk.json", drawings, {.units = "m"});
/// \endcode
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "breastfit/mesh/landmarks.h"

namespace breastfit::io {

struct MarkupsReadOptions {
  /// true: positions are converted to millimetres. false: positions keep the file's declared
  /// units (every markup must then declare the same units); MarkupsFile::units tells which.
  bool convert_to_mm = true;
};

/// A markups file's content plus the units of its positions.
struct MarkupsFile {
  Markups markups;          ///< positions in LPS, in `units`
  std::string units = "mm"; ///< "mm" or "m": units of the positions in `markups`
  std::vector<std::string> warnings;  ///< what was skipped (markup types, unplaced points)
};

/// Reads a markups file; positions in LPS millimetres. Drops the warnings (read_markups_file
/// keeps them).
/// \param[in] path  .mrk.json file
/// \throws IoError(path, problem) for a missing/unreadable file, malformed JSON, a document
///         that is not a markups file, an unsupported coordinate system or units, or a control
///         point without a finite position (the message names the markup and the point)
Markups read_markups(const std::filesystem::path& path);

/// Reads a markups file with explicit options (e.g. keeping the file's units).
/// \throws IoError as read_markups; also when convert_to_mm is false and the markups declare
///         different units
MarkupsFile read_markups_file(const std::filesystem::path& path, const MarkupsReadOptions& options);

/// Parses markups JSON text (what read_markups_file does after reading the file).
/// \param[in] text    the JSON document
/// \param[in] source  name used in error messages (a path, or e.g. "<string>")
/// \throws IoError(source, problem) as read_markups_file
MarkupsFile parse_markups(std::string_view text, const std::string& source,
                          const MarkupsReadOptions& options = {});

/// How write_markups encodes the file.
struct MarkupsWriteOptions {
  std::string units = "mm";              ///< "mm" or "m": units written (positions converted)
  std::string coordinate_system = "LPS"; ///< "LPS" or "RAS" (x and y negated for RAS)
  std::string points_name = "landmarks"; ///< name of the Fiducial markup holding the points
  /// Display colour (RGB in [0,1]) of the points in 3D Slicer, written as the Fiducial markup's
  /// `display` `color` and `selectedColor`; nullopt: no display block (Slicer's defaults).
  std::optional<std::array<double, 3>> points_color;

  /// \throws InvalidInput naming the field, value and accepted values
  void validate() const;
};

/// Formats markups as Slicer-loadable JSON text (see write_markups).
/// \param[in] markups    positions in LPS, in `input_units` ("mm" or "m")
/// \throws InvalidInput for invalid options, units or a non-finite position (naming it)
std::string format_markups(const Markups& markups, const MarkupsWriteOptions& options = {},
                           std::string_view input_units = "mm");

/// Writes markups as a Slicer-loadable `.mrk.json`: the points (if any) in one "Fiducial"
/// markup named options.points_name with each point's name as its control-point label, then one
/// "Curve" or "ClosedCurve" markup per curve. Every control point is written with id, label,
/// position, orientation, selected, locked, visibility and positionStatus "defined".
/// \param[in] path     destination (overwritten)
/// \param[in] markups  positions in LPS millimetres
/// \throws InvalidInput for invalid options or a non-finite position
/// \throws IoError(path, problem) when the file cannot be written
void write_markups(const std::filesystem::path& path, const Markups& markups,
                   const MarkupsWriteOptions& options = {});

}  // namespace breastfit::io
