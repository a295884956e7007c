#pragma once
// Synthetic cases on disk for the cohort tests: the default template's synthetic patients (synth
// layer), written in the bench layout, made once per test program and removed when it exits.
#include <unistd.h>

#include <filesystem>
#include <vector>

#include "breastfit/synth/case_writer.h"
#include "breastfit/synth/synth_case.h"
#include "support/default_template.h"

namespace breastfit::test {

/// Case directories <tmp>/case_<seed> for seeds 21 and 22.
inline const std::vector<std::filesystem::path>& cohort_test_cases() {
  struct Cases {
    std::filesystem::path root = std::filesystem::temp_directory_path() /
                                 ("breastfit_cohort_cases_" + std::to_string(::getpid()));
    std::vector<std::filesystem::path> dirs;
    Cases() {
      for (unsigned seed : {21u, 22u}) {
        synth::SynthOptions o;
        o.seed = seed;
        dirs.push_back(root / ("case_" + std::to_string(seed)));
        synth::write_case(dirs.back(), synth::make_case(*default_template(), o), true);
      }
    }
    ~Cases() {
      std::error_code ec;
      std::filesystem::remove_all(root, ec);
    }
  };
  static const Cases cases;
  return cases.dirs;
}

}  // namespace breastfit::test
