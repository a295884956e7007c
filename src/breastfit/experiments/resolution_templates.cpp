#include "breastfit/experiments/resolution_templates.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/core/timer.h"
#include "breastfit/model/gltf_io.h"
#include "breastfit/template/default_template.h"

namespace breastfit::experiments {
namespace {

namespace fs = std::filesystem;

/// FNV-1a over raw bytes.
struct Fnv {
  std::uint64_t h = 1469598103934665603ull;
  void bytes(const void* p, size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) {
      h ^= b[i];
      h *= 1099511628211ull;
    }
  }
  void number(double v) { bytes(&v, sizeof v); }
  void number(std::int64_t v) { bytes(&v, sizeof v); }
  void text(const std::string& s) { bytes(s.data(), s.size()); }
};

std::string edge_tag(double edge_mm) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", edge_mm);
  return buf;
}

}  // namespace

std::uint64_t template_fingerprint(const model::RiggedModel& m) {
  Fnv f;
  f.bytes(m.rest.V.data(), sizeof(double) * m.rest.V.size());
  f.bytes(m.rest.F.data(), sizeof(m.rest.F(0, 0)) * m.rest.F.size());
  f.bytes(m.weights.valuePtr(), sizeof(double) * m.weights.nonZeros());
  for (const auto& b : m.blendshapes) {
    f.text(b.name);
    f.bytes(b.displacements.data(), sizeof(double) * b.displacements.size());
    f.number(b.lo);
    f.number(b.hi);
  }
  for (const auto& l : m.landmarks) f.text(l.name);
  f.number(static_cast<std::int64_t>(m.drawings.size()));
  return f.h;
}

ResolutionTemplate resolution_template(double edge_mm, const fs::path& cache_dir, std::uint64_t base_fingerprint) {
  ResolutionTemplate out;
  templ::DefaultTemplateOptions o;
  out.edge_mm = edge_mm;
  out.grid_step_mm = std::min(o.grid_step_mm, 0.75 * edge_mm);
  o.target_edge_mm = edge_mm;
  o.grid_step_mm = out.grid_step_mm;
  o.validate();

  const nlohmann::json key = {{"edge_mm", out.edge_mm},
                              {"grid_step_mm", out.grid_step_mm},
                              {"base_fingerprint", std::to_string(base_fingerprint)}};
  fs::path sidecar;
  if (!cache_dir.empty()) {
    out.file = cache_dir / ("template_edge" + edge_tag(edge_mm) + "mm.glb");
    sidecar = fs::path(out.file).replace_extension(".json");
    if (fs::is_regular_file(out.file) && fs::is_regular_file(sidecar)) {
      std::ifstream f(sidecar);
      std::stringstream s;
      s << f.rdbuf();
      const nlohmann::json j = nlohmann::json::parse(s.str(), nullptr, /*allow_exceptions=*/false);
      if (j == key) {
        out.model = model::load_gltf(out.file);
        out.from_cache = true;
        return out;
      }
    }
  }
  Timer timer;
  out.model = templ::build_default_template(o);
  out.build_s = timer.seconds();
  if (!cache_dir.empty()) {
    fs::create_directories(cache_dir);
    model::save_gltf(out.file, out.model);
    // Use the model as stored, so that a run with a fresh cache and one reusing it agree.
    out.model = model::load_gltf(out.file);
    std::ofstream f(sidecar);
    if (!(f << key.dump(1) << "\n")) throw IoError(sidecar.string(), "cannot be written");
  }
  return out;
}

}  // namespace breastfit::experiments
