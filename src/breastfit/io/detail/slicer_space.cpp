#include "breastfit/io/detail/slicer_space.h"

namespace breastfit::io::detail {

SlicerSpace slicer_space_in_header(std::string_view header) {
  if (header.find("SPACE=RAS") != std::string_view::npos) return SlicerSpace::Ras;
  if (header.find("SPACE=LPS") != std::string_view::npos) return SlicerSpace::Lps;
  return SlicerSpace::Unstated;
}

SlicerSpace slicer_space_in_value(std::string_view value) {
  if (value.find("RAS") != std::string_view::npos) return SlicerSpace::Ras;
  if (value.find("LPS") != std::string_view::npos) return SlicerSpace::Lps;
  return SlicerSpace::Unstated;
}

void ras_to_lps(TriangleMesh& mesh) {
  mesh.V.leftCols(2) *= -1.0;
  if (mesh.N.rows() > 0) mesh.N.leftCols(2) *= -1.0;
}

}  // namespace breastfit::io::detail
