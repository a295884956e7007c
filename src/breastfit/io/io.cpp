#include "breastfit/io/io.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/io/read_obj.h"
#include "breastfit/io/read_ply.h"
#include "breastfit/io/read_stl.h"
#include "breastfit/io/read_vtk.h"
#include "breastfit/io/read_vtp.h"
#include "breastfit/io/write_obj.h"
#include "breastfit/io/write_ply.h"
#include "breastfit/io/write_stl.h"
#include "breastfit/io/write_vtk.h"

namespace breastfit::io {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

[[noreturn]] void unknown_extension(const std::filesystem::path& path, const std::string& ext,
                                   std::string_view supported) {
  throw IoError(path.string(), (ext.empty() ? std::string("no file extension")
                                            : "unknown mesh extension '" + ext + "'") +
                                   " (supported: " + std::string(supported) + ")");
}

}  // namespace

bool has_mesh_extension(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  return ext == ".ply" || ext == ".obj" || ext == ".stl" || ext == ".vtk" || ext == ".vtp";
}

TriangleMesh read_mesh(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".ply") return read_ply(path);
  if (ext == ".obj") return read_obj(path);
  if (ext == ".stl") return read_stl(path);
  if (ext == ".vtk") return read_vtk(path);
  if (ext == ".vtp") return read_vtp(path);
  unknown_extension(path, ext, kMeshExtensions);
}

void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                const MeshWriteOptions& options) {
  const std::string ext = lower_extension(path);
  if (ext == ".ply") {
    write_ply(path, mesh, options);
  } else if (ext == ".obj") {
    write_obj(path, mesh, options);
  } else if (ext == ".stl") {
    write_stl(path, mesh, options);
  } else if (ext == ".vtk") {
    write_vtk(path, mesh, options);
  } else {
    unknown_extension(path, ext, kMeshWriteExtensions);
  }
}

}  // namespace breastfit::io
