#pragma once
/// \file Writes a synthetic case in exactly the bench layout:
///   DIR/scan.ply                 binary little-endian PLY, float x,y,z, int32 faces
///   DIR/landmarks.mrk.json       input landmarks (Slicer markups, LPS, "mm" or ["m","UCUM","meter"])
///   DIR/truth/surface.ply        clean truth surface (same frame/units as the scan)
///   DIR/truth/landmarks.json     {name: [x, y, z]}
///   DIR/truth/curves.json        {name: {"closed": bool, "points": [[x, y, z], ...]}}
///   DIR/truth/landmarks.mrk.json the exact landmarks as markups
///   DIR/truth/meta.json          units, transform, generation parameters, statistics
#include <filesystem>
#include <string>
#include <vector>

#include "breastfit/synth/synth_case.h"

namespace breastfit::synth {

/// The files of a case, relative to its directory; truth/meta.json, written last, marks a
/// complete case.
std::vector<std::string> case_file_names();

/// Writes `c` into `dir` (created with its parents when missing) as one set (io/output_set.h):
/// the files are written next to `dir` and moved in together, truth/meta.json last, so an
/// interrupted run never leaves a mix of two cases. Other files in `dir` are not touched.
/// \param[in] force  overwrite an existing case; without it a directory that already holds a
///                   scan.ply or truth/ is refused
/// \throws IoError(dir, problem) when the case exists (without force) or a file cannot be written
void write_case(const std::filesystem::path& dir, const SynthCase& c, bool force);

/// The truth curves as bench JSON text ({name: {"closed", "points"}}).
std::string format_curves_json(const SynthCase& c);
/// The truth landmarks as bench JSON text ({name: [x, y, z]}).
std::string format_landmarks_json(const SynthCase& c);

}  // namespace breastfit::synth
