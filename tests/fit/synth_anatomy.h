#pragma once
/// \file Synthetic torsos (standing seed 11, supine seed 12, made once per test binary) and their
/// truth landmarks and body frame, for the tests of the anatomical detectors and checks (breast
/// fold, jugular notch, the midline notch, the bilateral pairs).
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "breastfit/fit/landmark_target.h"
#include "breastfit/synth/synth_case.h"
#include "support/default_template.h"

namespace breastfit::fit::test_anatomy {

/// The synthetic case of a pose, made on first use.
inline const synth::SynthCase& synth_case(synth::PoseType pose) {
  static std::map<synth::PoseType, synth::SynthCase> cases;
  auto it = cases.find(pose);
  if (it == cases.end()) {
    synth::SynthOptions o;
    o.seed = pose == synth::PoseType::Standing ? 11 : 12;
    o.pose = pose;
    it = cases.emplace(pose, synth::make_case(*test::default_template(), o)).first;
  }
  return it->second;
}

/// A truth landmark of the case by name (a test failure when absent).
inline Vec3 truth(const synth::SynthCase& c, const std::string& name) {
  for (const auto& p : c.truth_landmarks)
    if (p.name == name) return p.position;
  ADD_FAILURE() << "no truth landmark " << name;
  return Vec3::Zero();
}

/// The case's truth landmarks as given landmarks (weight 1; the model index is not used).
inline std::vector<LandmarkTarget> truth_targets(const synth::SynthCase& c) {
  std::vector<LandmarkTarget> out;
  for (const auto& p : c.truth_landmarks) out.push_back({p.name, 0, p.position, 1.0});
  return out;
}

/// The body's superior and anterior axes.
struct Frame {
  Vec3 up, front;
};

/// The body's frame from the truth: up along the sternum, front level through the nipples.
inline Frame body_frame(const synth::SynthCase& c) {
  const Vec3 up = (truth(c, "sternal_notch") - truth(c, "xiphoid")).normalized();
  Vec3 side = truth(c, "nipple_L") - truth(c, "nipple_R");
  side = (side - side.dot(up) * up).normalized();
  Vec3 front = up.cross(side);
  const Vec3 nipples = 0.5 * (truth(c, "nipple_L") + truth(c, "nipple_R"));
  if ((nipples - truth(c, "xiphoid")).dot(front) < 0) front = -front;
  return {up, front};
}

}  // namespace breastfit::fit::test_anatomy
