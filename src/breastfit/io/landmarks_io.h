#pragma once
/// \file Reading the anatomical landmarks a registration is guided by.
///
/// Formats, chosen by extension (case-insensitive):
///  - `.mrk.json` — 3D Slicer markups (see markups.h): the control points of every "Fiducial"
///    point list, named by their labels (curves are ignored); RAS is converted to LPS; what the
///    markups reader skipped (unplaced points, other markup types) is in LandmarkSet::warnings;
///  - `.json` — `{"name": [x, y, z], ...}` (a `.json` holding a "markups" array is read as
///    markups);
///  - `.csv` — one `name,x,y,z` per line; an optional header line (e.g. `name,x,y,z`), blank
///    lines and `#` comments are skipped; spaces around fields are ignored; a line without
///    commas may separate its four fields by blanks;
///  - `.fcsv` — legacy 3D Slicer fiducial list: `#` header lines (`# CoordinateSystem = RAS`,
///    `LPS`, `0` = RAS or `1` = LPS, RAS when absent; `# columns = id,x,y,z,...,label,...`,
///    Slicer's column order when absent), then one row per point named by its `label`; RAS is
///    converted to LPS as for markups; positions are millimetres (declared_units "mm").
///
/// Units: markups files declare them, the positions are returned in the declared units (not
/// converted) with LandmarkSet::declared_units set; plain JSON and CSV cannot, so
/// declared_units is nullopt and the caller decides (usually the scan's units, see
/// landmarks_to_mm).
///
/// Example:
/// \code
///   breastfit::LandmarkSet lm = breastfit::io::read_landmarks("landmarks.mrk.json");
///   lm = breastfit::io::landmarks_to_mm(lm, scan_units);
///   if (const breastfit::Vec3* p = lm.find("nipple_L")) { ... }
/// \endcode
#include <filesystem>
#include <string_view>

#include "breastfit/mesh/landmarks.h"
#include "breastfit/mesh/units.h"

namespace breastfit::io {

/// The landmark file extensions read_landmarks accepts, as error messages list them.
inline constexpr std::string_view kLandmarkExtensions = ".mrk.json, .json, .csv, .fcsv";

struct LandmarkReadOptions {
  bool require_known_names = true;  ///< every name must be one of kLandmarkNames (landmark_names.h)
};

/// Reads and validates a landmark file.
/// \param[in] path     .mrk.json, .json, .csv or .fcsv file
/// \param[in] options  validation options
/// \return unique, finite, named positions in LPS, in the file's units, in file order
/// \throws IoError(path, problem) with a one-line message for: a missing/unreadable file, an
///         unsupported extension, an empty file, malformed JSON/CSV or wrong shapes (naming the
///         line or landmark), an unknown name (listing the expected names), a duplicate name,
///         a NaN/Inf coordinate (naming the landmark), or a file with no landmarks
LandmarkSet read_landmarks(const std::filesystem::path& path, const LandmarkReadOptions& options = {});

/// The landmarks in millimetres: converted with their declared units when the file declared
/// them, otherwise with `undeclared_units` (typically the scan's units). The result declares "mm".
/// \throws InvalidInput if declared_units is neither "mm" nor "m"
LandmarkSet landmarks_to_mm(const LandmarkSet& landmarks, mesh::Units undeclared_units);

}  // namespace breastfit::io
