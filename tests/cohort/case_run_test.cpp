// One case of a cohort: the register output set in its sub-directory, the record, resuming, a bad
// case recorded as failed.
#include "breastfit/cohort/case_run.h"

#include <gtest/gtest.h>

#include <fstream>

#include "cohort_test_cases.h"
#include "support/test_paths.h"

namespace breastfit::cohort {
namespace {

namespace fs = std::filesystem;

CaseRunOptions options() {
  CaseRunOptions o;
  o.model = test::default_template();
  o.report_html = false;
  return o;
}

TEST(CaseRun, RegistersResumesAndForces) {
  const fs::path out = test::temp_dir();
  const auto c = resolve_case_argument(test::cohort_test_cases()[0])[0];
  const CaseRecord r = run_case(c, out, options());
  ASSERT_EQ(r.status, "ok") << r.message;
  EXPECT_FALSE(r.resumed);
  EXPECT_TRUE(r.wall_s && r.time_s && *r.wall_s >= *r.time_s);
  EXPECT_LT(*r.surface_mae_mm, 2.0);
  EXPECT_TRUE(r.landmark_mae_mm && r.volume_right_ml && r.inter_nipple_mm);
  for (const char* f : {"fitted.ply", "params.json", "drawings.mrk.json", "report.json"})
    EXPECT_TRUE(fs::exists(out / c.name / f)) << f;
  EXPECT_FALSE(fs::exists(out / c.name / "report.html"));

  const auto stamp = fs::last_write_time(out / c.name / "fitted.ply");
  const CaseRecord again = run_case(c, out, options());
  EXPECT_TRUE(again.resumed);
  EXPECT_FALSE(again.wall_s);
  EXPECT_EQ(again.surface_mae_mm, r.surface_mae_mm);
  EXPECT_EQ(again.time_s, r.time_s);
  EXPECT_EQ(fs::last_write_time(out / c.name / "fitted.ply"), stamp);
  EXPECT_TRUE(finished_record(out, c));

  CaseRunOptions force = options();
  force.force = true;
  EXPECT_FALSE(run_case(c, out, force).resumed);

  std::ofstream(out / c.name / "report.json") << "{ damaged";  // not a finished run: fitted again
  EXPECT_FALSE(finished_record(out, c));
  EXPECT_FALSE(run_case(c, out, options()).resumed);
}

TEST(CaseRun, BadCaseIsAFailedRecord) {
  const fs::path d = test::temp_dir();
  std::ofstream(d / "broken.ply") << "ply\nformat ascii 1.0\nelement vertex 2\nend_header\n1 2 3\n";
  const CaseRecord r = run_case(CohortCase{"broken", d / "broken.ply", std::nullopt}, d / "out", options());
  EXPECT_EQ(r.status, "failed");
  EXPECT_FALSE(r.finished());
  EXPECT_NE(r.message.find("broken.ply"), std::string::npos) << r.message;
  EXPECT_FALSE(fs::exists(d / "out" / "broken" / "report.json"));

  // Landmarks that do not parse: failed too, naming the landmark file.
  const auto good = resolve_case_argument(test::cohort_test_cases()[1])[0];
  std::ofstream(d / "bad.mrk.json") << "[]";
  const CaseRecord l = run_case(CohortCase{"l", good.scan, d / "bad.mrk.json"}, d / "out", options());
  EXPECT_EQ(l.status, "failed");
  EXPECT_NE(l.message.find("bad.mrk.json"), std::string::npos) << l.message;
  CaseRunOptions ignore = options();
  ignore.ignore_landmarks = true;
  const CaseRecord free = run_case(CohortCase{"l", good.scan, d / "bad.mrk.json"}, d / "out", ignore);
  EXPECT_EQ(free.status, "ok") << free.message;
  EXPECT_FALSE(free.landmark_mae_mm);
}

}  // namespace
}  // namespace breastfit::cohort
