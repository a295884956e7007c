// A landmark moved along the skin, on synthetic scans made from the template (standing and
// supine): the fit follows it, the leave-one-out prediction does not.
#include "breastfit/fit/landmark_prediction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <string>

#include "breastfit/fit/bilateral_check.h"
#include "breastfit/fit/landmark_check.h"
#include "breastfit/fit/pectoral_insertion.h"
#include "breastfit/fit/problem.h"
#include "breastfit/fit/registration.h"
#include "breastfit/fit/stage_minimizer.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/synth/synth_case.h"
#include "support/default_template.h"
#include "support/test_shapes.h"

namespace breastfit::fit {
namespace {

// Of the 24 moves per case (12 landmarks, 20 and 40 mm): floors two below the measured counts (22
// standing, 18 supine with the combined, apex and xiphoid checks of session 13; 19 and 18 before,
// 16 and 16 before the bilateral pairs' check; docs/REGISTRATION.md, "Checking the landmarks a
// person placed"): a borderline move can go either way with the number of threads the fit gets.
constexpr int kMinFlaggedStanding = 20;
constexpr int kMinFlaggedSupine = 16;

const synth::SynthCase& synth_case(int seed, synth::PoseType pose) {
  static std::map<std::pair<int, synth::PoseType>, synth::SynthCase> cases;
  auto it = cases.find({seed, pose});
  if (it == cases.end()) {
    synth::SynthOptions o;
    o.seed = static_cast<std::uint64_t>(seed);
    o.pose = pose;
    it = cases.emplace(std::make_pair(seed, pose), synth::make_case(*test::default_template(), o)).first;
  }
  return it->second;
}

std::vector<std::pair<std::string, Vec3>> given(const synth::SynthCase& c) {
  std::vector<std::pair<std::string, Vec3>> out;
  for (const auto& p : c.input_landmarks) out.emplace_back(p.name, p.position);
  return out;
}

// `p` walked `length_mm` along the scan's skin in the tangent direction at `angle` (2 mm steps,
// each snapped back onto the scan).
Vec3 moved_along_skin(const ScanTarget& scan, const Vec3& p, double length_mm, double angle) {
  ScanMatch m = scan.closest(p);
  const Vec3 n = m.normal;
  const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
  Vec3 dir = std::cos(angle) * a + std::sin(angle) * b;
  Vec3 q = m.point;
  for (double walked = 0; walked < length_mm; walked += 2.0) {
    dir = (dir - dir.dot(m.normal) * m.normal).normalized();
    m = scan.closest(q + 2.0 * dir);
    q = m.point;
  }
  return q;
}

const LandmarkCheck* find(const FitSummary& s, const std::string& name) {
  for (const auto& c : s.landmark_checks)
    if (c.name == name) return &c;
  return nullptr;
}

// Walks each landmark 20 and 40 mm along the skin in a direction from a fixed seed, registers,
// and counts how often the moved landmark is flagged. The landmarks as given: no flag.
int flagged_moves(int seed, synth::PoseType pose, int* trials) {
  const auto& model = *test::default_template();
  const synth::SynthCase& c = synth_case(seed, pose);
  ScanTarget scan(c.scan);
  const auto lms = given(c);
  const FitOptions o;
  const FitResult base = register_template(model, scan, match_landmarks(model, lms), o);
  for (const auto& ch : base.summary.landmark_checks) {
    EXPECT_FALSE(ch.flagged) << ch.name << " as given: predicted " << ch.predicted_distance_mm << " mm, anatomy "
                             << ch.anatomy_distance_mm << " mm";
    EXPECT_GE(ch.predicted_distance_mm, 0.0) << ch.name;
  }
  std::mt19937 rng(static_cast<unsigned>(seed));
  int flagged = 0;
  *trials = 0;
  for (size_t k = 0; k < lms.size(); ++k)
    for (double d : {20.0, 40.0}) {
      auto moved = lms;
      moved[k].second = moved_along_skin(scan, lms[k].second, d, 2 * M_PI * (rng() / 4294967296.0));
      const FitResult r = register_template(model, scan, match_landmarks(model, moved), o);
      const LandmarkCheck* ch = find(r.summary, lms[k].first);
      ++*trials;
      if (ch && ch->flagged) ++flagged;
      if (std::getenv("BREASTFIT_VERBOSE"))
        std::printf("%s %2.0f mm: fitted %5.1f predicted %5.1f anatomy %5.1f flagged %d\n", lms[k].first.c_str(), d,
                    ch->distance_mm, ch->predicted_distance_mm, ch->anatomy_distance_mm, ch->flagged);
    }
  return flagged;
}

TEST(LandmarkPrediction, FlagsLandmarksMovedAlongTheSkinStanding) {
  int trials = 0;
  const int flagged = flagged_moves(23, synth::PoseType::Standing, &trials);
  EXPECT_GE(flagged, kMinFlaggedStanding) << "of " << trials;
}

TEST(LandmarkPrediction, FlagsLandmarksMovedAlongTheSkinSupine) {
  int trials = 0;
  const int flagged = flagged_moves(22, synth::PoseType::Supine, &trials);
  EXPECT_GE(flagged, kMinFlaggedSupine) << "of " << trials;
}

// A clearly wrong click (the xiphoid 40 mm along the skin) is held off: the fit stays near the
// one with the landmark as given, nearer than when the check is switched off.
TEST(LandmarkPrediction, AFlaggedLandmarkDoesNotDragTheFit) {
  const auto& model = *test::default_template();
  const synth::SynthCase& c = synth_case(21, synth::PoseType::Standing);
  ScanTarget scan(c.scan);
  const ScanTarget truth(c.truth_surface, 300);
  auto lms = given(c);
  const auto mean_to_truth = [&](const FitResult& r) {
    double sum = 0;
    for (Index i = 0; i < r.model_vertices.rows(); ++i)
      sum += std::sqrt(truth.closest(r.model_vertices.row(i).transpose()).sq_dist);
    return sum / r.model_vertices.rows();
  };
  const FitOptions o;
  const double as_given = mean_to_truth(register_template(model, scan, match_landmarks(model, lms), o));
  const size_t k = 1;
  ASSERT_EQ(lms[k].first, "xiphoid");
  lms[k].second = moved_along_skin(scan, lms[k].second, 40.0, 1.0);
  const FitResult held = register_template(model, scan, match_landmarks(model, lms), o);
  const LandmarkCheck* ch = find(held.summary, "xiphoid");
  ASSERT_TRUE(ch && ch->flagged);
  EXPECT_LT(ch->factor, 0.5);
  bool warned = false;
  for (const auto& w : held.summary.warnings)
    warned = warned || w.find("'xiphoid' is") != std::string::npos;
  EXPECT_TRUE(warned);
  FitOptions off;
  off.landmark_check_mm = 1e6;  // no landmark beyond its tolerance: nothing held off
  const double dragged = mean_to_truth(register_template(model, scan, match_landmarks(model, lms), off));
  const double with_check = mean_to_truth(held);
  EXPECT_LT(with_check, dragged);
  EXPECT_LT(with_check, as_given + 0.5) << "as given " << as_given << ", dragged " << dragged;
}

// The template-made standing torso of seed 3 drawn in the scanner's axes (no misalignment: X is
// the patient's left), with less annotation noise than the default (1 mm) so that nothing is
// flagged as given; made once for the tests that move one of its landmarks.
const synth::SynthCase& aligned_seed3_case() {
  static const synth::SynthCase c = [] {
    synth::SynthOptions so;
    so.seed = 3;
    so.misalign_rotation_deg = 0.0;
    so.misalign_translation_m = 0.0;
    so.landmark_noise_mm = 1.0;
    return synth::make_case(*test::default_template(), so);
  }();
  return c;
}

// The options of the tests on aligned_seed3_case: the template-made torso's right nipple lies
// 24 mm below its breast's apex on the scan and lower on its breast than the left one (the
// template's nipple is not at its breast's apex), which the nipples' below-the-apex rule flags
// (FitOptions::nipple_below_apex_check); the tests below are of other rules.
FitOptions seed3_options() {
  FitOptions o;
  o.nipple_below_apex_check = false;
  return o;
}

// The below-the-apex rule reaches the registration: on the seed-3 torso as given, the right nipple
// (the template's, 24 mm below its breast's apex, lower than the left one on its own) is flagged
// by that rule, and the left one is not; with the rule off neither is.
TEST(LandmarkPrediction, TheNippleBelowItsApexAndItsPartnerIsFlaggedInTheFit) {
  const auto& model = *test::default_template();
  const synth::SynthCase& c = aligned_seed3_case();
  ScanTarget scan(c.scan);
  const auto lms = match_landmarks(model, given(c));
  const FitResult on = register_template(model, scan, lms, FitOptions{});
  const LandmarkCheck* right = find(on.summary, "nipple_R");
  const LandmarkCheck* left = find(on.summary, "nipple_L");
  ASSERT_NE(right, nullptr);
  ASSERT_NE(left, nullptr);
  EXPECT_TRUE(right->flagged);
  EXPECT_NE(right->anatomy.find("below it and lower on its breast than the other nipple"), std::string::npos)
      << right->anatomy;
  EXPECT_FALSE(left->flagged) << left->anatomy;
  const FitResult off = register_template(model, scan, lms, seed3_options());
  EXPECT_FALSE(find(off.summary, "nipple_R")->flagged);
}

// A lowest breast point moved 20 mm sideways, within what its pair's mirror check tolerates, where
// that check blames its partner: the moved one is flagged because it enters the combined check
// with the pair's asymmetry (bilateral_check.h unblamed_member; without that it is not flagged).
// The case is drawn in the scanner's axes (no misalignment: X is the patient's left), with less
// annotation noise than the default so that nothing is flagged as given.
TEST(LandmarkPrediction, APairMemberNotBlamedIsCheckedWithTheOthers) {
  const auto& model = *test::default_template();
  const synth::SynthCase& c = aligned_seed3_case();
  ScanTarget scan(c.scan);
  auto lms = given(c);
  const FitOptions o = seed3_options();
  const FitResult as_given = register_template(model, scan, match_landmarks(model, lms), o);
  for (const auto& ch : as_given.summary.landmark_checks) EXPECT_FALSE(ch.flagged) << ch.name << " as given";
  const size_t k = 11;
  ASSERT_EQ(lms[k].first, "lowest_breast_L");
  lms[k].second.x() += 20.0;
  const auto pair = check_bilateral_pairs(match_landmarks(model, lms), o.landmark_check_mm);
  const auto lowest = std::find_if(pair.begin(), pair.end(), [](const BilateralCheck& b) { return b.left == "lowest_breast_L"; });
  ASSERT_NE(lowest, pair.end());
  ASSERT_TRUE(unblamed_member(*lowest).has_value()) << "the pair's check flags it by itself: no test of the rule";
  EXPECT_EQ(*unblamed_member(*lowest), "lowest_breast_L");
  const FitResult moved = register_template(model, scan, match_landmarks(model, lms), o);
  const LandmarkCheck* ch = find(moved.summary, "lowest_breast_L");
  ASSERT_NE(ch, nullptr);
  EXPECT_TRUE(ch->flagged) << "fitted " << ch->distance_mm << " mm, predicted " << ch->predicted_distance_mm
                           << " mm, anatomy " << ch->anatomy_distance_mm << " mm";
}

// An acromion walked 20 mm along the skin puts its pair beyond the tolerance, and the proportions
// blame its partner; the walked one's prediction moved, its partner's did not, so the pair's check
// goes to the walked one (bilateral_check.h blamed_by_prediction; without it the partner is flagged
// and the walked one is not). The template-made standing torso of seed 3 in the scanner's axes,
// annotation noise 1 mm (nothing flagged as given: APairMemberNotBlamedIsCheckedWithTheOthers).
TEST(LandmarkPrediction, APairBeyondItsToleranceBlamesTheMemberWhosePredictionMoved) {
  const auto& model = *test::default_template();
  const synth::SynthCase& c = aligned_seed3_case();
  ScanTarget scan(c.scan);
  auto lms = given(c);
  const size_t k = 2;
  ASSERT_EQ(lms[k].first, "acromion_R");
  lms[k].second = moved_along_skin(scan, lms[k].second, 20.0, M_PI);
  const FitOptions o = seed3_options();
  const auto pairs = check_bilateral_pairs(match_landmarks(model, lms), o.landmark_check_mm);
  const auto acromia = std::find_if(pairs.begin(), pairs.end(), [](const BilateralCheck& b) { return b.right == "acromion_R"; });
  ASSERT_NE(acromia, pairs.end());
  ASSERT_TRUE(acromia->flagged()) << "the pair is within its tolerance: no test of the rule";
  ASSERT_EQ(acromia->blamed, "acromion_L") << "the proportions blame the walked one already: no test of the rule";
  const FitResult moved = register_template(model, scan, match_landmarks(model, lms), o);
  const LandmarkCheck* walked = find(moved.summary, "acromion_R");
  const LandmarkCheck* partner = find(moved.summary, "acromion_L");
  ASSERT_NE(walked, nullptr);
  ASSERT_NE(partner, nullptr);
  EXPECT_TRUE(walked->flagged) << "predicted " << walked->predicted_distance_mm << " mm, anatomy "
                               << walked->anatomy_distance_mm << " mm";
  EXPECT_FALSE(partner->flagged) << partner->anatomy;
}

// A floating fragment (a small sphere, radius 3 mm) 25 mm in front of a nipple placed right: over
// every scan vertex the breast's tip would be the fragment, beyond the tip's tolerance (18 mm); on
// the skin (skin_around.h, session 20) it is not, and nothing is flagged. The template-made
// standing torso of seed 3 in the scanner's axes (nothing flagged as given without the fragment:
// APairMemberNotBlamedIsCheckedWithTheOthers).
TEST(LandmarkPrediction, AFragmentInFrontOfTheBreastIsNotItsTip) {
  const auto& model = *test::default_template();
  const synth::SynthCase& c = aligned_seed3_case();
  const auto lms = given(c);
  const auto nipple = std::find_if(lms.begin(), lms.end(), [](const auto& l) { return l.first == "nipple_L"; });
  ASSERT_NE(nipple, lms.end());
  TriangleMesh with_fragment = c.scan;
  {
    const ScanTarget plain(c.scan);
    const ScanMatch m = plain.closest(nipple->second);
    const TriangleMesh fragment = test::sphere_mesh(3.0, m.point + 25.0 * m.normal, 6, 12);
    const Index n = with_fragment.V.rows(), f = with_fragment.F.rows();
    with_fragment.V.conservativeResize(n + fragment.V.rows(), 3);
    with_fragment.V.bottomRows(fragment.V.rows()) = fragment.V;
    with_fragment.F.conservativeResize(f + fragment.F.rows(), 3);
    with_fragment.F.bottomRows(fragment.F.rows()) = (fragment.F.array() + n).matrix();
    const Points N = mesh::vertex_normals(with_fragment);
    const auto tip = breast_tip_on_scan(with_fragment.V, with_fragment.V, N, nipple->second);
    ASSERT_TRUE(tip);
    ASSERT_GT((*tip - nipple->second).norm(), FitOptions{}.nipple_tip_check_mm) << "the fragment is not the tip: no test of the rule";
  }
  ScanTarget scan(with_fragment);
  const FitResult r = register_template(model, scan, match_landmarks(model, lms), seed3_options());
  for (const auto& ch : r.summary.landmark_checks)
    EXPECT_FALSE(ch.flagged) << ch.name << ": anatomy " << ch.anatomy_distance_mm << " mm (" << ch.anatomy << ")";
}

// The prediction of a landmark left out moves the model back towards where the others put it: a
// landmark walked 40 mm is predicted farther from where it was placed than the fit leaves it.
TEST(LandmarkPrediction, LeavingALandmarkOutMovesTheModelBack) {
  const auto& model = *test::default_template();
  const synth::SynthCase& c = synth_case(22, synth::PoseType::Supine);
  ScanTarget scan(c.scan);
  auto lms = given(c);
  lms[0].second = moved_along_skin(scan, lms[0].second, 40.0, 0.5);  // the sternal notch
  const FitOptions o;
  FitOptions off = o;
  off.landmark_check_mm = 1e6;
  off.notch_check_mm = 1e6;  // the notch's own check would hold it off too: the fit must follow it here
  const FitResult r = register_template(model, scan, match_landmarks(model, lms), off);
  const LandmarkCheck* ch = find(r.summary, lms[0].first);
  ASSERT_NE(ch, nullptr);
  EXPECT_GT(ch->predicted_distance_mm, ch->distance_mm + 3.0);
}

// Re-linearised leave-one-out steps follow the path back over the curved skin that one linear
// step cuts short: a pectoral insertion walked 30 mm is predicted farther from the click, and the
// problem is left as it was.
TEST(LandmarkPrediction, RelinearizedStepsRecoverMoreOfAMove) {
  const auto& model = *test::default_template();
  const synth::SynthCase& c = synth_case(23, synth::PoseType::Standing);
  ScanTarget scan(c.scan);
  auto lms = given(c);
  const size_t k = 6;
  ASSERT_EQ(lms[k].first, "pectoral_insertion_R");
  lms[k].second = moved_along_skin(scan, lms[k].second, 30.0, 2.0);
  FitOptions off;
  off.landmark_check_mm = 1e6;  // nothing held off: the fit follows the click
  const auto targets = match_landmarks(model, lms);
  const FitResult r = register_template(model, scan, targets, off);
  Problem problem(model, scan, off, targets);
  problem.evaluator().set_params(r.params);
  const Relinearization at_end{off.correspondences.max_distance_end_mm, off.uses_reverse_term(), true};
  problem.update_correspondences(at_end.max_distance_mm, 1, at_end.with_reverse);
  problem.update_terms(at_end.robust_landmarks);
  const double energy = problem.evaluate(nullptr).total();
  const auto active = active_parameters(problem.evaluator().layout(), off.refine, off.max_blendshapes);
  const Vec3 linear = predict_left_out_landmarks(problem, r.params, active)[k];
  const Vec3 relinearized = predict_left_out_relinearized(problem, r.params, active, k, 4, at_end);
  const Vec3& click = lms[k].second;
  EXPECT_GT((relinearized - click).norm(), (linear - click).norm() + 2.0)
      << "linear " << (linear - click).norm() << " mm, re-linearised " << (relinearized - click).norm() << " mm";
  // One step is the linear prediction.
  EXPECT_LT((predict_left_out_relinearized(problem, r.params, active, k, 1, at_end) - linear).norm(), 1e-6);
  EXPECT_NEAR(problem.evaluate(nullptr).total(), energy, 1e-9 * std::max(1.0, energy));
}

}  // namespace
}  // namespace breastfit::fit

namespace breastfit::fit {
namespace {

double angle_deg(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
}

// The fitted upper arm follows a misplaced pectoral insertion; the insertion's own leave-one-out
// step turns it back towards the arm the scan and the other landmarks give, so the insertion's check
// reads that arm (registration.cpp left_out_insertion_arms; docs/REGISTRATION.md, session 22).
TEST(LandmarkPrediction, TheInsertionsLeftOutStepTurnsTheArmBack) {
  const auto& model = *test::default_template();
  const synth::SynthCase& c = synth_case(22, synth::PoseType::Supine);
  ScanTarget scan(c.scan);
  FitOptions off;
  off.landmark_check_mm = 1e6;  // nothing held off: the fit follows the click
  const auto arm_of = [&](const std::vector<std::pair<std::string, Vec3>>& lms, bool left_out) {
    const auto targets = match_landmarks(model, lms);
    const FitResult r = register_template(model, scan, targets, off);
    Problem problem(model, scan, off, targets);
    problem.evaluator().set_params(r.params);
    problem.update_correspondences(off.correspondences.max_distance_end_mm, 1, off.uses_reverse_term());
    problem.update_terms(off.refine.robust_landmarks);
    model::PoseParams at = r.params;
    if (left_out) {
      std::vector<model::PoseParams> steps;
      const auto active = active_parameters(problem.evaluator().layout(), off.refine, off.max_blendshapes);
      predict_left_out_landmarks(problem, r.params, active, &steps);
      at = steps.at(7);
    }
    problem.evaluator().set_params(at);
    return upper_arm_axis(model, problem.evaluator().vertices(), at, "L");
  };
  auto lms = given(c);
  ASSERT_EQ(lms[7].first, "pectoral_insertion_L");
  const auto as_given = arm_of(lms, false);
  lms[7].second = moved_along_skin(scan, lms[7].second, 40.0, 1.0);
  const auto fitted = arm_of(lms, false), left_out = arm_of(lms, true);
  ASSERT_TRUE(as_given && fitted && left_out);
  const double turned = angle_deg(*fitted, *as_given), back = angle_deg(*left_out, *as_given);
  // Measured: turned 48.5°, 28.5° at the left-out step.
  EXPECT_GT(turned, 20.0) << "the fitted arm no longer follows the click: the premise of this test";
  EXPECT_LT(back, turned - 10.0) << "the fitted arm turned " << turned << "°, at the left-out step " << back << "°";
}

}  // namespace
}  // namespace breastfit::fit
