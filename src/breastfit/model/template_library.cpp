#include "breastfit/model/template_library.h"

#include <cstdlib>
#include <system_error>

#include "breastfit/core/errors.h"
#include "breastfit/model/gltf_io.h"

namespace breastfit::model {
namespace {

std::filesystem::path executable_dir() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  return exe.parent_path();
}

const char* env_template() {
  const char* env = std::getenv("BREASTFIT_TEMPLATE");
  return (env && *env) ? env : nullptr;
}

}  // namespace

std::vector<std::filesystem::path> default_template_candidates() {
  std::vector<std::filesystem::path> out;
  if (const char* env = env_template()) out.emplace_back(env);
  const auto exe_dir = executable_dir();
  if (!exe_dir.empty()) out.push_back((exe_dir / ".." / "share" / "breastfit" / kDefaultTemplateFile).lexically_normal());
  out.push_back(std::filesystem::path(BREASTFIT_SOURCE_DIR) / "assets" / "templates" / kDefaultTemplateFile);
  return out;
}

std::filesystem::path default_template_path() {
  std::error_code ec;
  if (const char* env = env_template()) {
    const std::filesystem::path p(env);
    if (!std::filesystem::is_regular_file(p, ec))
      throw IoError(p.string(), "BREASTFIT_TEMPLATE names a file that does not exist");
    return p;
  }
  std::string tried;
  for (const auto& p : default_template_candidates()) {
    if (std::filesystem::is_regular_file(p, ec)) return p;
    tried += (tried.empty() ? "" : ", ") + p.string();
  }
  throw IoError(kDefaultTemplateFile, "default template not found (tried " + tried +
                                          "; set BREASTFIT_TEMPLATE or run `breastfit template build`)");
}

RiggedModel load_default_template() { return load_gltf(default_template_path()); }

}  // namespace breastfit::model
