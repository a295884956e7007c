#include "breastfit/io/write_vtk.h"

#include <bit>
#include <cstdint>
#include <string>

#include "breastfit/io/detail/file_bytes.h"
#include "breastfit/io/detail/mesh_arrays.h"
#include "breastfit/io/detail/text.h"

namespace breastfit::io {
namespace {

/// Appends `value` big-endian (the legacy format's binary byte order).
template <typename T>
void put_big_endian(std::string& out, T value) {
  using Bits = std::conditional_t<sizeof(T) == 8, std::uint64_t, std::uint32_t>;
  const auto bits = std::bit_cast<Bits>(value);
  for (int k = static_cast<int>(sizeof(T)) - 1; k >= 0; --k) {
    out.push_back(static_cast<char>((bits >> (8 * k)) & 0xff));
  }
}

/// Writes the values of a #rows x cols matrix row by row, one row per line in ascii.
class ValueWriter {
 public:
  ValueWriter(std::string& out, const MeshWriteOptions& options) : out_(out), options_(options) {}

  template <typename Matrix>
  void reals(const Matrix& m) {
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
      for (Eigen::Index c = 0; c < m.cols(); ++c) real(static_cast<double>(m(r, c)), c + 1 == m.cols());
    }
    if (options_.binary) out_ += '\n';
  }

  void real(double v, bool last) {
    if (options_.binary) {
      if (options_.double_precision) {
        put_big_endian(out_, v);
      } else {
        put_big_endian(out_, static_cast<float>(v));
      }
      return;
    }
    out_ += options_.double_precision ? detail::format_double(v)
                                      : detail::format_float(static_cast<float>(v));
    out_ += last ? '\n' : ' ';
  }

  const char* real_type() const { return options_.double_precision ? "double" : "float"; }

 private:
  std::string& out_;
  const MeshWriteOptions& options_;
};

}  // namespace

std::string write_vtk_to_memory(const TriangleMesh& mesh, const MeshWriteOptions& options) {
  detail::check_mesh_for_writing(mesh);
  std::string out = "# vtk DataFile Version 3.0\nbreastfit SPACE=LPS\n";
  out += options.binary ? "BINARY\n" : "ASCII\n";
  out += "DATASET POLYDATA\n";
  ValueWriter values(out, options);
  out += "POINTS " + std::to_string(mesh.V.rows()) + " " + values.real_type() + "\n";
  values.reals(mesh.V);
  if (mesh.F.rows() > 0) {
    out += "POLYGONS " + std::to_string(mesh.F.rows()) + " " + std::to_string(4 * mesh.F.rows()) + "\n";
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      if (options.binary) {
        put_big_endian(out, std::int32_t{3});
        for (int k = 0; k < 3; ++k) put_big_endian(out, static_cast<std::int32_t>(mesh.F(f, k)));
      } else {
        out += "3 " + std::to_string(mesh.F(f, 0)) + " " + std::to_string(mesh.F(f, 1)) + " " +
               std::to_string(mesh.F(f, 2)) + "\n";
      }
    }
    if (options.binary) out += '\n';
  }
  const bool normals = options.normals && mesh.has_normals();
  const bool colors = options.colors && mesh.has_colors();
  const bool uv = options.texcoords && mesh.has_texcoords() && mesh.FUV == mesh.F &&
                  mesh.UV.rows() == mesh.V.rows();
  if (!normals && !colors && !uv) return out;
  out += "POINT_DATA " + std::to_string(mesh.V.rows()) + "\n";
  if (normals) {
    out += std::string("NORMALS Normals ") + values.real_type() + "\n";
    values.reals(mesh.N);
  }
  if (colors) {
    out += "COLOR_SCALARS Colors 3\n";
    if (options.binary) {
      for (Eigen::Index i = 0; i < mesh.C.size(); ++i) out += static_cast<char>(mesh.C.data()[i]);
      out += '\n';
    } else {
      values.reals((mesh.C.cast<double>() / 255.0).eval());
    }
  }
  if (uv) {
    out += std::string("TEXTURE_COORDINATES TCoords 2 ") + values.real_type() + "\n";
    values.reals(mesh.UV);
  }
  return out;
}

void write_vtk(const std::filesystem::path& path, const TriangleMesh& mesh,
               const MeshWriteOptions& options) {
  detail::write_file_bytes(path, write_vtk_to_memory(mesh, options));
}

}  // namespace breastfit::io
