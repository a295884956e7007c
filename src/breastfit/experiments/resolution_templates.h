#pragma once
/// \file Templates of several resolutions for the resolution experiment (the paper, §4: "the
/// refinement of the mesh can lead to better registration with a slight increase of the
/// registration time"): the default template rebuilt by templ::build_default_template with only
/// the target edge length changed, cached as .glb so that a second run does not rebuild them.
#include <cstdint>
#include <filesystem>
#include <string>

#include "breastfit/model/rigged_model.h"

namespace breastfit::experiments {

struct ResolutionTemplate {
  double edge_mm = 16.0;        ///< target edge length given to the builder
  double grid_step_mm = 7.0;    ///< marching-tetrahedra step (min(default, 0.75 · edge))
  model::RiggedModel model;
  double build_s = 0;           ///< builder time (0 when loaded from the cache)
  bool from_cache = false;
  std::filesystem::path file;   ///< the cached .glb (empty without a cache directory)
};

/// A fingerprint of a template (rest mesh, skin weights, blendshapes, landmarks): cached
/// templates are rebuilt when the default template they were derived from has changed.
std::uint64_t template_fingerprint(const model::RiggedModel& model);

/// The default template built with target edge `edge_mm`. With a cache directory, reuses
/// `cache_dir`/template_edge<edge>mm.glb when its sidecar .json records the same edge, grid step
/// and `base_fingerprint` (the fingerprint of the default template the run uses), else builds
/// and writes both (and then uses the model as read back from the file, so that runs with a
/// fresh cache and with a reused one agree). \throws InvalidInput for an edge the builder refuses; IoError when the
/// cache cannot be written.
ResolutionTemplate resolution_template(double edge_mm, const std::filesystem::path& cache_dir,
                                       std::uint64_t base_fingerprint);

}  // namespace breastfit::experiments
