#pragma once
/// \file A registration request for a synthetic case: its scan and given landmarks, the shipped
/// template (shared by the pipeline and transfer tests that register synthetic cases).
#include "support/default_template.h"
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/synth/synth_case.h"

namespace breastfit::test {

/// A registration request for a synthetic case: its scan and landmarks, the shipped template.
inline pipeline::RegisterRequest synth_request(const synth::SynthCase& c) {
  pipeline::RegisterRequest req;
  req.scan = c.scan;
  req.model = test::default_template();
  LandmarkSet lms;
  lms.points = c.input_landmarks;
  req.landmarks = lms;
  return req;
}

}  // namespace breastfit::test
