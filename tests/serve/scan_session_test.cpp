#include "breastfit/serve/scan_session.h"

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/synth/synth_case.h"
#include "support/default_template.h"
#include "support/test_paths.h"

namespace breastfit::serve {
namespace {

struct Case {
  std::filesystem::path scan = test::temp_dir() / "scan.ply";
  LandmarkSet landmarks;
  Case() {
    synth::SynthOptions o;
    o.seed = 11;
    const synth::SynthCase c = synth::make_case(*test::default_template(), o);
    io::write_mesh(scan, c.scan);
    landmarks.points = c.input_landmarks;
    landmarks.declared_units = "mm";
  }
};

const Case& the_case() {
  static const Case c;
  return c;
}

TEST(ScanSession, WarmRefitStartsFromThePreviousFit) {
  ScanSession s("1", the_case().scan, "scan.ply", test::default_template());
  EXPECT_GT(s.scan().mesh_mm.F.rows(), 0);
  const auto cold = s.run_fit(the_case().landmarks, true);  // nothing to warm-start from yet
  ASSERT_TRUE(cold->result.usable()) << cold->result.fit.summary.message;
  EXPECT_FALSE(cold->warm);
  EXPECT_EQ(cold->generation, 1);
  EXPECT_EQ(cold->distances_mm.size(), static_cast<size_t>(cold->result.fit.vertices.rows()));

  LandmarkSet moved = the_case().landmarks;
  moved.points[8].position.z() += 3.0;
  const auto warm = s.run_fit(moved, true);
  ASSERT_TRUE(warm->result.usable());
  EXPECT_TRUE(warm->warm);
  EXPECT_EQ(warm->result.fit.summary.initialization, "warm start");
  ASSERT_EQ(warm->result.fit.summary.stages.size(), 1u);
  EXPECT_EQ(warm->result.fit.summary.stages[0].name, "refine");
  EXPECT_LT(warm->result.fit.summary.iterations.size(), cold->result.fit.summary.iterations.size());
  // Close to the full fit: the mean surface error does not get worse by more than a tenth of a mm.
  EXPECT_LT(warm->result.surface.mae, cold->result.surface.mae + 0.1);
}

TEST(ScanSession, OneFitAtATimeAndCancel) {
  fit::FitOptions o;
  o.solver.function_tolerance = 1e-300;
  o.solver.gradient_tolerance = o.solver.parameter_tolerance = 0;
  for (auto* st : o.stages()) st->max_iterations = 400;
  ScanSession s("1", the_case().scan, "scan.ply", test::default_template(), o);
  ASSERT_TRUE(s.start_fit(the_case().landmarks, false));
  EXPECT_FALSE(s.start_fit(the_case().landmarks, false));
  EXPECT_EQ(s.status().state, FitState::Running);
  int used = 0;
  EXPECT_FALSE(s.with_target([&](const fit::ScanTarget&) { ++used; }));  // the fit owns the index
  s.cancel();
  s.wait();
  EXPECT_TRUE(s.with_target([&](const fit::ScanTarget& t) { used += t.mesh().F.rows() > 0; }));
  EXPECT_EQ(used, 1);
  const FitStatus st = s.status();
  EXPECT_EQ(st.state, FitState::Cancelled);
  EXPECT_EQ(st.outcome, nullptr);
  EXPECT_LT(st.iterations, 5 * 400);
}

TEST(ScanSession, BadInputsAreReported) {
  EXPECT_THROW(ScanSession("1", test::temp_dir() / "none.ply", "none.ply", test::default_template()), IoError);
  ScanSession s("1", the_case().scan, "scan.ply", test::default_template());
  LandmarkSet bad;
  bad.points = {{"belly_button", Vec3(0, 0, 0)}};
  bad.declared_units = "mm";
  ASSERT_TRUE(s.start_fit(bad, false));
  s.wait();
  EXPECT_EQ(s.status().state, FitState::Failed);
  EXPECT_NE(s.status().message.find("belly_button"), std::string::npos) << s.status().message;
}

}  // namespace
}  // namespace breastfit::serve
