#pragma once
/// \file glTF 2.0 load/save of the rigged template (docs/TEMPLATE_FORMAT.md).
///
/// A template is one skinned triangle mesh: the skin's joints are the bones, the morph targets
/// are the blendshapes (named by `mesh.extras.targetNames`, as Blender writes them), and what
/// glTF has no slot for (bone pivots, rest axes, scale bounds, blendshape bounds, landmarks,
/// drawings, regions) lives in `extras.breastfit` objects. Files without those extras — e.g. a
/// rig exported from Blender — load with defaults: pivots at the joints' world positions, rest
/// axes identity, scale bounds [0.5, 2], blendshape bounds [0, 1] (Blender's slider range).
///
/// Frames and units: glTF geometry is in metres, +Y up, the asset facing +Z (glTF spec); the
/// model is in millimetres in the body frame LPS. Loading maps a glTF point p to
/// 1000 · (p.x, −p.z, p.y) and saving maps back, so the written file looks right in any glTF
/// viewer (and in Blender). Values in `extras.breastfit` are stored in the model frame (mm, LPS)
/// as JSON doubles, so they round-trip exactly; vertex data round-trips within float32 precision.
///
/// Example:
/// \code
///   breastfit::model::RiggedModel m = breastfit::model::load_gltf("default_torso.glb");
///   breastfit::model::save_gltf("copy.gltf", m);
/// \endcode
#include <filesystem>
#include <string>

#include "breastfit/model/rigged_model.h"

namespace breastfit::model {

/// Loads a rigged template from a `.gltf` (JSON, buffers embedded as base64 data URIs or in
/// external files next to it) or `.glb` (binary) file.
///
/// The mesh is the node with both a mesh and a skin (else the first node with a mesh; it then
/// gets a single bone "root" at the mesh centroid). A file with several skinned meshes is
/// refused with their names unless `mesh` names one (its node's or its mesh's name). All triangle primitives of that mesh
/// (mode 4 triangles, 5 strips and 6 fans; strips and fans triangulated) are concatenated in
/// order (face indices of landmarks and drawings refer to that order).
/// Up to 8 influences per vertex (JOINTS_0/WEIGHTS_0, JOINTS_1/WEIGHTS_1) are read and
/// renormalised; a vertex without any weight is bound to the first root bone. Bones are
/// ordered parents first (the joint order of the skin otherwise). Morph targets may use sparse
/// accessors. Files without breastfit extras have coincident vertices welded when their
/// positions, weights and morph displacements are bit-identical (Blender splits vertices at UV
/// seams and sharp edges).
/// \param[in] path  file to read (extension .gltf or .glb, case-insensitive)
/// \return the model, which passes RiggedModel::validate()
/// \param[in] mesh  which skinned mesh to load when the file has several (empty: the only one)
/// \throws IoError(path, problem) for a missing or malformed file (a glTF 1.0 file and a skin
///         without joints are named as such), an unsupported extension, several skinned meshes
///         and no (or an unknown) `mesh`, an accessor out of bounds, or extras that do not fit
///         the mesh
RiggedModel load_gltf(const std::filesystem::path& path, const std::string& mesh = "");

/// Saves a rigged template as glTF 2.0: `.gltf` with the buffer embedded as a base64 data URI,
/// or `.glb`, chosen by extension (case-insensitive). Writes one skinned mesh (positions,
/// normals, indices, JOINTS_0/WEIGHTS_0 and, when a vertex has more than 4 influences,
/// JOINTS_1/WEIGHTS_1), the bones as joint nodes under an "Armature" node (translation-only,
/// inverse bind matrices at the pivots), one sparse morph target per blendshape, and the
/// breastfit extras.
/// \param[in] path   destination (overwritten)
/// \param[in] model  the template
/// \throws InvalidInput if the model fails validate() or a vertex has more than 8 influences
/// \throws IoError(path, problem) for an unsupported extension or a failed write
void save_gltf(const std::filesystem::path& path, const RiggedModel& model);

}  // namespace breastfit::model
