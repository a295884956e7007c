#pragma once
// A small procedural rigged model for the tests of every layer: an elliptic cylinder "torso"
// (410 vertices, 816 triangles, closed, outward counter-clockwise triangles, mm, LPS: +z up,
// −y anterior) with
//  - 4 bones in a chain pelvis → spine → chest → neck, pivots on the axis, non-trivial rest axes,
//    distinct scale bounds;
//  - smooth skin weights with up to 3 influences per vertex;
//  - 6 blendshapes: "bulge" [-1,1], "taper" [0,1.5], "twist" [-2,2] (global), "breast_R" [0,1],
//    "breast_L" [-0.5,1], "dent" [-1,0.5] (local bumps);
//  - landmarks "sternal_notch", "nipple_R", "nipple_L" (the nipples at the breast bump apexes);
//  - drawings "sternum" (open, anterior midline) and "breast_contour_R" (closed, around breast_R);
//  - region "breast_R" (the vertices the breast_R shape moves).
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "breastfit/mesh/triangle_mesh.h"

#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::test {

/// The toy model described above (deterministic; validate() passes).
model::RiggedModel make_toy_model();

/// A random non-trivial pose of `model` within its bounds: global rotation up to ~0.3 rad,
/// translation up to 20 mm, scale in [0.9, 1.1]; bone rotations up to 0.25·amplitude rad,
/// translations up to 4·amplitude mm, scales and blendshape weights uniform within their bounds
/// (shrunk towards the rest value by `amplitude` ∈ (0, 1]).
model::PoseParams random_toy_pose(const model::RiggedModel& model, std::uint64_t seed, double amplitude = 1.0);

/// A noise-free "scan": the toy model posed by random_toy_pose(seed, amplitude), with its
/// landmarks exactly on it.
struct ToyScanCase {
  ToyScanCase(std::uint64_t seed, double amplitude);
  model::RiggedModel m;
  model::PoseParams truth;
  TriangleMesh mesh;
  /// The model's landmarks on the posed mesh, by name.
  std::vector<std::pair<std::string, Vec3>> named_landmarks() const;
};

}  // namespace breastfit::test

namespace breastfit::test {
/// The toy model saved as `dir`/two.gltf with two skinned mesh nodes, 'First' and 'Second'
/// (the same mesh): a template file that needs --mesh NAME. Returns its path.
std::filesystem::path save_two_mesh_toy(const std::filesystem::path& dir);
}  // namespace breastfit::test
