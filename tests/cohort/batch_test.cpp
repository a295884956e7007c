// A cohort on a pool of threads: records in case order whatever finishes first, a failing case
// among good ones, progress called once per case, cohort.csv and cohort.html.
#include "breastfit/cohort/batch.h"

#include <gtest/gtest.h>

#include <fstream>

#include "breastfit/cohort/cohort_csv.h"
#include "breastfit/core/errors.h"
#include "cohort_test_cases.h"
#include "support/test_paths.h"

namespace breastfit::cohort {
namespace {

namespace fs = std::filesystem;

TEST(Batch, ThreadsGiveTheRecordsInCaseOrderAndTheSameResults) {
  const fs::path d = test::temp_dir();
  std::ofstream(d / "broken.stl") << "solid x\nfacet normal 0 0 1\nendsolid\n";
  std::vector<CohortCase> cases = resolve_cases({test::cohort_test_cases()[0], d / "broken.stl", test::cohort_test_cases()[1]});
  BatchOptions o;
  o.run.model = test::default_template();
  o.run.report_html = false;
  o.jobs = 2;
  std::vector<int> done;
  const auto records = run_batch(cases, d / "out2", o, [&](int n, int total, const CaseRecord&) {
    EXPECT_EQ(total, 3);
    done.push_back(n);
  });
  EXPECT_EQ(done, (std::vector<int>{1, 2, 3}));
  ASSERT_EQ(records.size(), 3u);
  EXPECT_EQ(records[0].name, "case_21");
  EXPECT_EQ(records[1].status, "failed");
  EXPECT_EQ(records[2].name, "case_22");
  EXPECT_EQ(records[0].status, "ok");
  EXPECT_EQ(records[2].status, "ok");

  o.jobs = 1;
  const auto serial = run_batch(cases, d / "out1", o);
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(serial[i].surface_mae_mm, records[i].surface_mae_mm) << i;
  for (const char* f : {"params.json", "fitted.ply"}) {
    std::ifstream a(d / "out1" / "case_22" / f, std::ios::binary), b(d / "out2" / "case_22" / f, std::ios::binary);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}), std::string(std::istreambuf_iterator<char>(b), {})) << f;
  }

  write_cohort_summary(d / "out2", records);
  std::ifstream csv(d / "out2" / "cohort.csv");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(csv), {}), format_cohort_csv(records));
  EXPECT_TRUE(fs::exists(d / "out2" / "cohort.html"));
  EXPECT_FALSE(fs::exists(d / "out2" / ".cohort.csv.tmp"));

  o.jobs = 0;
  EXPECT_THROW(run_batch(cases, d / "out3", o), InvalidInput);
}

}  // namespace
}  // namespace breastfit::cohort
