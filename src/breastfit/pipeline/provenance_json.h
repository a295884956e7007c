#pragma once
/// \file Provenance → report.json's `provenance` block (deterministic: version, inputs with
/// SHA-256, effective fit options) and `run` block (start time, command line).
#include <nlohmann/json.hpp>

#include "breastfit/pipeline/provenance.h"

namespace breastfit::pipeline {

/// {"breastfit_version", "inputs": {role: {"path", "sha256"}}, "fit_options": fit::to_json}.
nlohmann::json provenance_json(const Provenance& p);

/// {"started_utc", "command_line"}.
nlohmann::json run_json(const Provenance& p);

}  // namespace breastfit::pipeline
