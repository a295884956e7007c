#pragma once
// The pipeline benchmarks' case: a synthetic case (seed 3, the default template) written to a
// temporary directory (no external data), read back and registered once; removed at exit.
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>

#include <unistd.h>

#include "breastfit/io/io.h"
#include "breastfit/io/landmarks_io.h"
#include "breastfit/model/template_library.h"
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/synth/case_writer.h"
#include "breastfit/synth/synth_case.h"

namespace breastfit::bench {

struct RegisteredCase {
  std::filesystem::path dir;  ///< holds case/ (scan.ply, landmarks.mrk.json, truth/)
  std::shared_ptr<const model::RiggedModel> model;
  pipeline::RegisterRequest request;
  pipeline::RegisterResult result;

  /// `name`: the temporary directory's prefix, e.g. "breastfit-phases-bench".
  explicit RegisteredCase(const std::string& name)
      : dir(std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()))) {
    model = std::make_shared<const model::RiggedModel>(model::load_default_template());
    synth::SynthOptions so;
    so.seed = 3;
    synth::write_case(dir / "case", synth::make_case(*model, so), true);
    request.scan = io::read_mesh(dir / "case" / "scan.ply");
    request.landmarks = io::read_landmarks(dir / "case" / "landmarks.mrk.json");
    request.model = model;
    result = pipeline::register_scan(request);
  }
  ~RegisteredCase() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  RegisteredCase(const RegisteredCase&) = delete;
  RegisteredCase& operator=(const RegisteredCase&) = delete;
};

}  // namespace breastfit::bench
