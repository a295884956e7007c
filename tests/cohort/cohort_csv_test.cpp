// cohort.csv: header, empty fields for missing numbers, quoting.
#include "breastfit/cohort/cohort_csv.h"

#include <gtest/gtest.h>

#include <sstream>

namespace breastfit::cohort {
namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

TEST(CohortCsv, RowsInOrderWithEmptyFieldsForMissingNumbers) {
  CaseRecord ok;
  ok.name = "p1";
  ok.scan = "cases/p1/scan.ply";
  ok.status = "ok";
  ok.time_s = 0.123456;
  ok.surface_mae_mm = 0.6543217;
  ok.iterations = 40;
  ok.warnings = 1;
  CaseRecord failed;
  failed.name = "p2";
  failed.scan = "p2,old.ply";
  failed.message = "p2,old.ply: bad \"header\"";
  const auto l = lines(format_cohort_csv({ok, failed}));
  ASSERT_EQ(l.size(), 3u);
  EXPECT_EQ(l[0].substr(0, 28), "case,status,resumed,time_s,w");
  const auto columns = cohort_csv_columns();
  EXPECT_EQ(std::count(l[0].begin(), l[0].end(), ','), static_cast<long>(columns.size() - 1));
  EXPECT_EQ(l[1], "p1,ok,no,0.1235,,40,0.654322,,,,,,,,,,,,1,cases/p1/scan.ply,");
  EXPECT_EQ(l[2], "p2,failed,no,,,,,,,,,,,,,,,,0,\"p2,old.ply\",\"p2,old.ply: bad \"\"header\"\"\"");
}

}  // namespace
}  // namespace breastfit::cohort
