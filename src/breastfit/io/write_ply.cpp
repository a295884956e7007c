#include "breastfit/io/write_ply.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

#include "breastfit/io/detail/file_bytes.h"
#include "breastfit/io/detail/mesh_arrays.h"
#include "breastfit/io/detail/text.h"

namespace breastfit::io {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the binary PLY writer assumes a little-endian host");

template <typename T>
void put(std::string& out, T value) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  out.append(b, sizeof(T));
}

void put_real(std::string& out, double value, bool binary, bool use_double) {
  if (binary) {
    if (use_double) {
      put(out, value);
    } else {
      put(out, static_cast<float>(value));
    }
  } else {
    out +=
        use_double ? detail::format_double(value) : detail::format_float(static_cast<float>(value));
  }
}

}  // namespace

std::string write_ply_to_memory(const TriangleMesh& mesh, const MeshWriteOptions& options) {
  detail::check_mesh_for_writing(mesh);
  const bool binary = options.binary;
  const bool dbl = options.double_precision;
  const bool normals = options.normals && mesh.has_normals();
  const bool colors = options.colors && mesh.has_colors();
  const bool uv = options.texcoords && mesh.has_texcoords() && mesh.UV.rows() == mesh.V.rows() &&
                  mesh.FUV == mesh.F;
  const char* real = dbl ? "double" : "float";

  std::string out;
  out += "ply\n";
  out += binary ? "format binary_little_endian 1.0\n" : "format ascii 1.0\n";
  out += "comment written by breastfit\n";
  out += "element vertex " + std::to_string(mesh.V.rows()) + "\n";
  for (const char* p : {"x", "y", "z"}) out += std::string("property ") + real + " " + p + "\n";
  if (normals) {
    for (const char* p : {"nx", "ny", "nz"})
      out += std::string("property ") + real + " " + p + "\n";
  }
  if (colors) out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (uv) out += std::string("property ") + real + " u\nproperty " + real + " v\n";
  if (mesh.F.rows() > 0) {
    out += "element face " + std::to_string(mesh.F.rows()) + "\n";
    out += "property list uchar int vertex_indices\n";
  }
  out += "end_header\n";

  const std::size_t per_vertex =
      binary ? (dbl ? 8 : 4) * (3 + (normals ? 3 : 0) + (uv ? 2 : 0)) + (colors ? 3 : 0)
             : 16 * (3 + (normals ? 3 : 0) + (uv ? 2 : 0) + (colors ? 3 : 0));
  out.reserve(out.size() + per_vertex * static_cast<std::size_t>(mesh.V.rows()) +
              (binary ? 13 : 40) * static_cast<std::size_t>(mesh.F.rows()));

  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    bool first = true;
    auto sep = [&] {
      if (!binary && !first) out += ' ';
      first = false;
    };
    for (int k = 0; k < 3; ++k) {
      sep();
      put_real(out, mesh.V(i, k), binary, dbl);
    }
    if (normals) {
      for (int k = 0; k < 3; ++k) {
        sep();
        put_real(out, mesh.N(i, k), binary, dbl);
      }
    }
    if (colors) {
      for (int k = 0; k < 3; ++k) {
        sep();
        if (binary) {
          put(out, mesh.C(i, k));
        } else {
          out += std::to_string(static_cast<int>(mesh.C(i, k)));
        }
      }
    }
    if (uv) {
      for (int k = 0; k < 2; ++k) {
        sep();
        put_real(out, mesh.UV(i, k), binary, dbl);
      }
    }
    if (!binary) out += '\n';
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    if (binary) {
      put(out, std::uint8_t{3});
      for (int k = 0; k < 3; ++k) put(out, static_cast<std::int32_t>(mesh.F(f, k)));
    } else {
      out += "3 " + std::to_string(mesh.F(f, 0)) + " " + std::to_string(mesh.F(f, 1)) + " " +
             std::to_string(mesh.F(f, 2)) + "\n";
    }
  }
  return out;
}

void write_ply(const std::filesystem::path& path, const TriangleMesh& mesh,
               const MeshWriteOptions& options) {
  detail::write_file_bytes(path, write_ply_to_memory(mesh, options));
}

}  // namespace breastfit::io
