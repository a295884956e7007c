#include "breastfit/io/write_stl.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "breastfit/io/detail/file_bytes.h"
#include "breastfit/io/detail/mesh_arrays.h"
#include "breastfit/io/detail/text.h"
#include "breastfit/mesh/normals.h"

namespace breastfit::io {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the binary STL writer assumes a little-endian host");

void put_float(std::string& out, double v) {
  const float f = static_cast<float>(v);
  char b[4];
  std::memcpy(b, &f, 4);
  out.append(b, 4);
}

}  // namespace

std::string write_stl_to_memory(const TriangleMesh& mesh, const MeshWriteOptions& options) {
  detail::check_mesh_for_writing(mesh);
  const Points N = mesh::face_normals(mesh);  // zero rows for degenerate triangles
  std::string out;
  if (options.binary) {
    std::string header = "binary STL written by breastfit";
    header.resize(80, ' ');
    out += header;
    const auto count = static_cast<std::uint32_t>(mesh.F.rows());
    char b[4];
    std::memcpy(b, &count, 4);
    out.append(b, 4);
    out.reserve(84 + 50 * static_cast<std::size_t>(count));
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      const Eigen::Vector3d n = N.row(f).transpose();
      for (int k = 0; k < 3; ++k) put_float(out, n[k]);
      for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < 3; ++k) put_float(out, mesh.V(mesh.F(f, c), k));
      }
      out.append(2, '\0');
    }
    return out;
  }
  // STL stores single precision: write the float value in the shortest text that reads back
  // (as double) to exactly that float.
  auto number = [](double v) { return detail::format_double(static_cast<float>(v)); };
  out += "solid breastfit\n";
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d n = N.row(f).transpose();
    out += "  facet normal " + number(n[0]) + " " + number(n[1]) + " " + number(n[2]) + "\n";
    out += "    outer loop\n";
    for (int c = 0; c < 3; ++c) {
      const Eigen::Index v = mesh.F(f, c);
      out += "      vertex " + number(mesh.V(v, 0)) + " " + number(mesh.V(v, 1)) + " " +
             number(mesh.V(v, 2)) + "\n";
    }
    out += "    endloop\n  endfacet\n";
  }
  out += "endsolid breastfit\n";
  return out;
}

void write_stl(const std::filesystem::path& path, const TriangleMesh& mesh,
               const MeshWriteOptions& options) {
  detail::write_file_bytes(path, write_stl_to_memory(mesh, options));
}

}  // namespace breastfit::io
