#pragma once
/// \file The colour image of a textured OBJ: the OBJ's `mtllib` names a material library (.mtl)
/// whose `map_Kd` names the image (PNG, JPEG) its `vt` coordinates index. read_obj keeps the
/// coordinates (TriangleMesh::UV, FUV); this finds the image, for display (the workstation shows
/// the scan textured). One image per scan: the first `map_Kd` of the first library.
#include <filesystem>
#include <string>

namespace breastfit::io {

struct ObjTexture {
  std::filesystem::path mtl;    ///< the material library, or empty when the OBJ names none
  std::filesystem::path image;  ///< the colour image (not checked to exist), or empty
  /// Why there is no image although the OBJ names a library ("… .mtl is missing", "… has no
  /// map_Kd"), empty otherwise.
  std::string problem;
};

/// The texture image of `obj` (`mtllib` resolved against the OBJ's folder, `map_Kd` against the
/// library's; `map_Kd` options such as `-s 1 1 1` skipped).
/// \throws IoError when `obj` cannot be read
ObjTexture obj_texture(const std::filesystem::path& obj);

}  // namespace breastfit::io
