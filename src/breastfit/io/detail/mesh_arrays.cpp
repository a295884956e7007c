#include "breastfit/io/detail/mesh_arrays.h"

#include <string>

#include "breastfit/core/errors.h"

namespace breastfit::io::detail {

namespace {
template <typename Matrix, typename T>
Matrix copy_rows(const std::vector<T>& flat) {
  const Eigen::Index cols = Matrix::ColsAtCompileTime;
  Matrix out(static_cast<Eigen::Index>(flat.size()) / cols, cols);
  for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] = flat[static_cast<std::size_t>(i)];
  return out;
}
}  // namespace

Points to_points(const std::vector<double>& flat) { return copy_rows<Points>(flat); }
Triangles to_triangles(const std::vector<Index>& flat) { return copy_rows<Triangles>(flat); }
TexCoords to_texcoords(const std::vector<double>& flat) { return copy_rows<TexCoords>(flat); }
Colors to_colors(const std::vector<std::uint8_t>& flat) { return copy_rows<Colors>(flat); }

void check_mesh_for_writing(const TriangleMesh& mesh) {
  const Eigen::Index nv = mesh.V.rows();
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index v = mesh.F(f, k);
      if (v < 0 || v >= nv) {
        throw InvalidInput("cannot write mesh: face " + std::to_string(f) + " references vertex " +
                           std::to_string(v) + " but the mesh has " + std::to_string(nv) +
                           " vertices");
      }
    }
  }
  if (mesh.N.rows() != 0 && mesh.N.rows() != nv) {
    throw InvalidInput("cannot write mesh: N has " + std::to_string(mesh.N.rows()) +
                       " rows but V has " + std::to_string(nv));
  }
  if (mesh.C.rows() != 0 && mesh.C.rows() != nv) {
    throw InvalidInput("cannot write mesh: C has " + std::to_string(mesh.C.rows()) +
                       " rows but V has " + std::to_string(nv));
  }
  if (mesh.FUV.rows() != 0) {
    if (mesh.FUV.rows() != mesh.F.rows()) {
      throw InvalidInput("cannot write mesh: FUV has " + std::to_string(mesh.FUV.rows()) +
                         " rows but F has " + std::to_string(mesh.F.rows()));
    }
    const Eigen::Index nt = mesh.UV.rows();
    for (Eigen::Index f = 0; f < mesh.FUV.rows(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const Index t = mesh.FUV(f, k);
        if (t < 0 || t >= nt) {
          throw InvalidInput("cannot write mesh: face " + std::to_string(f) +
                             " references texture coordinate " + std::to_string(t) +
                             " but UV has " + std::to_string(nt) + " rows");
        }
      }
    }
  }
}

}  // namespace breastfit::io::detail
