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

void put_text_real(std::string& out, double value, bool use_double) {
  out += use_double ? detail::format_double(value) : detail::format_float(static_cast<float>(value));
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

  if (binary) {
    // Sized once and filled through a pointer: no capacity check per value.
    const std::size_t header = out.size();
    out.resize(header + per_vertex * static_cast<std::size_t>(mesh.V.rows()) +
               13 * static_cast<std::size_t>(mesh.F.rows()));
    char* w = out.data() + header;
    auto emit = [&w](auto value) {
      std::memcpy(w, &value, sizeof(value));
      w += sizeof(value);
    };
    auto emit_real = [&](double value) {
      if (dbl) {
        emit(value);
      } else {
        emit(static_cast<float>(value));
      }
    };
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
      for (int k = 0; k < 3; ++k) emit_real(mesh.V(i, k));
      if (normals) {
        for (int k = 0; k < 3; ++k) emit_real(mesh.N(i, k));
      }
      if (colors) {
        for (int k = 0; k < 3; ++k) emit(mesh.C(i, k));
      }
      if (uv) {
        for (int k = 0; k < 2; ++k) emit_real(mesh.UV(i, k));
      }
    }
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      emit(std::uint8_t{3});
      for (int k = 0; k < 3; ++k) emit(static_cast<std::int32_t>(mesh.F(f, k)));
    }
    return out;
  }
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    bool first = true;
    auto sep = [&] {
      if (!first) out += ' ';
      first = false;
    };
    for (int k = 0; k < 3; ++k) {
      sep();
      put_text_real(out, mesh.V(i, k), dbl);
    }
    if (normals) {
      for (int k = 0; k < 3; ++k) {
        sep();
        put_text_real(out, mesh.N(i, k), dbl);
      }
    }
    if (colors) {
      for (int k = 0; k < 3; ++k) {
        sep();
        out += std::to_string(static_cast<int>(mesh.C(i, k)));
      }
    }
    if (uv) {
      for (int k = 0; k < 2; ++k) {
        sep();
        put_text_real(out, mesh.UV(i, k), dbl);
      }
    }
    out += '\n';
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    out += "3 " + std::to_string(mesh.F(f, 0)) + " " + std::to_string(mesh.F(f, 1)) + " " +
           std::to_string(mesh.F(f, 2)) + "\n";
  }
  return out;
}

void write_ply(const std::filesystem::path& path, const TriangleMesh& mesh,
               const MeshWriteOptions& options) {
  detail::write_file_bytes(path, write_ply_to_memory(mesh, options));
}

}  // namespace breastfit::io
