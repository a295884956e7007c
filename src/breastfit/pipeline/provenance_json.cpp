#include "breastfit/pipeline/provenance_json.h"

#include "breastfit/fit/fit_options_json.h"

namespace breastfit::pipeline {

nlohmann::json provenance_json(const Provenance& p) {
  nlohmann::json inputs = nlohmann::json::object();
  for (const InputFile& f : p.inputs) inputs[f.role] = {{"path", f.path}, {"sha256", f.sha256}};
  return {{"breastfit_version", p.version}, {"inputs", inputs}, {"fit_options", fit::to_json(p.options)}};
}

nlohmann::json run_json(const Provenance& p) {
  return {{"started_utc", p.started_utc}, {"command_line", p.command_line}};
}

}  // namespace breastfit::pipeline
