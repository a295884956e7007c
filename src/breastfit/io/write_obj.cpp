#include "breastfit/io/write_obj.h"

#include <string>

#include "breastfit/io/detail/file_bytes.h"
#include "breastfit/io/detail/mesh_arrays.h"
#include "breastfit/io/detail/text.h"

namespace breastfit::io {

std::string write_obj_to_memory(const TriangleMesh& mesh, const MeshWriteOptions& options) {
  detail::check_mesh_for_writing(mesh);
  const bool normals = options.normals && mesh.has_normals();
  const bool colors = options.colors && mesh.has_colors();
  const bool uv = options.texcoords && mesh.has_texcoords();
  std::string out = "# written by breastfit\n";
  out.reserve(out.size() + 64 * static_cast<std::size_t>(mesh.V.rows()) +
              32 * static_cast<std::size_t>(mesh.F.rows()));
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    out += "v";
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      out += detail::format_double(mesh.V(i, k));
    }
    if (colors) {
      for (int k = 0; k < 3; ++k) {
        out += ' ';
        out += detail::format_double(static_cast<double>(mesh.C(i, k)) / 255.0);
      }
    }
    out += '\n';
  }
  if (uv) {
    for (Eigen::Index i = 0; i < mesh.UV.rows(); ++i) {
      out += "vt ";
      out += detail::format_double(mesh.UV(i, 0));
      out += ' ';
      out += detail::format_double(mesh.UV(i, 1));
      out += '\n';
    }
  }
  if (normals) {
    for (Eigen::Index i = 0; i < mesh.N.rows(); ++i) {
      out += "vn";
      for (int k = 0; k < 3; ++k) {
        out += ' ';
        out += detail::format_double(mesh.N(i, k));
      }
      out += '\n';
    }
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    out += "f";
    for (int k = 0; k < 3; ++k) {
      const std::string v = std::to_string(mesh.F(f, k) + 1);
      out += ' ';
      out += v;
      if (uv) {
        out += '/';
        out += std::to_string(mesh.FUV(f, k) + 1);
      }
      if (normals) {
        out += uv ? "/" : "//";
        out += v;
      }
    }
    out += '\n';
  }
  return out;
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const MeshWriteOptions& options) {
  detail::write_file_bytes(path, write_obj_to_memory(mesh, options));
}

}  // namespace breastfit::io
