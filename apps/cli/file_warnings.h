#pragma once
/// \file Reading markups and landmark files with what their readers skipped (other markup
/// types, control points Slicer left unplaced) printed as warnings on stderr.
#include <string>
#include <vector>

#include "breastfit/io/landmarks_io.h"
#include "breastfit/io/markups.h"

namespace breastfit::cli {

/// Prints each warning as "breastfit: warning: <file>: <warning>" on stderr.
void print_file_warnings(const std::string& file, const std::vector<std::string>& warnings);

/// io::read_markups_file with its warnings printed. \throws IoError as io::read_markups_file.
io::MarkupsFile read_markups_warning(const std::string& path, const io::MarkupsReadOptions& options = {});

/// io::read_landmarks with its warnings printed. \throws IoError as io::read_landmarks.
LandmarkSet read_landmarks_warning(const std::string& path, const io::LandmarkReadOptions& options = {});

}  // namespace breastfit::cli
