#pragma once
/// \file Locating and loading the shipped default template (default_torso.glb).
#include <filesystem>
#include <vector>

#include "breastfit/model/rigged_model.h"

namespace breastfit::model {

/// File name of the shipped default template.
inline constexpr const char* kDefaultTemplateFile = "default_torso.glb";

/// Where the default template is looked for, in order:
///  1. the environment variable BREASTFIT_TEMPLATE (when set and non-empty),
///  2. <directory of the running executable>/../share/breastfit/default_torso.glb (installed),
///  3. <source tree>/assets/templates/default_torso.glb (build tree).
std::vector<std::filesystem::path> default_template_candidates();

/// The first existing candidate of default_template_candidates(). When BREASTFIT_TEMPLATE is
/// set it is the only candidate tried (an explicit choice never falls back silently).
/// \throws IoError naming the paths tried when none exists
std::filesystem::path default_template_path();

/// load_gltf(default_template_path()).
/// \throws IoError as default_template_path() and load_gltf()
RiggedModel load_default_template();

}  // namespace breastfit::model
