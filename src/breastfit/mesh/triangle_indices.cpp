#include "breastfit/mesh/triangle_indices.h"

#include <string>

#include "breastfit/core/errors.h"

namespace breastfit::mesh {

void check_triangle_indices(const Triangles& F, Index num_vertices) {
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (F(f, c) < 0 || F(f, c) >= num_vertices)
        throw InvalidInput("triangle " + std::to_string(f) + " has vertex index " +
                           std::to_string(F(f, c)) + " outside [0, " +
                           std::to_string(num_vertices) + ")");
}

}  // namespace breastfit::mesh
