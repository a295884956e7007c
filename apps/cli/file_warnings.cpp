#include "file_warnings.h"

#include <iostream>

namespace breastfit::cli {

void print_file_warnings(const std::string& file, const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) std::cerr << "breastfit: warning: " << file << ": " << w << "\n";
}

io::MarkupsFile read_markups_warning(const std::string& path, const io::MarkupsReadOptions& options) {
  io::MarkupsFile file = io::read_markups_file(path, options);
  print_file_warnings(path, file.warnings);
  return file;
}

LandmarkSet read_landmarks_warning(const std::string& path, const io::LandmarkReadOptions& options) {
  LandmarkSet landmarks = io::read_landmarks(path, options);
  print_file_warnings(path, landmarks.warnings);
  return landmarks;
}

}  // namespace breastfit::cli
