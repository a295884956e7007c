// cohort.html: counts, one histogram per metric, outliers by robust z, failed cases with reasons,
// escaped names.
#include "breastfit/cohort/cohort_html.h"

#include <gtest/gtest.h>

namespace breastfit::cohort {
namespace {

std::vector<CaseRecord> cohort() {
  std::vector<CaseRecord> rs;
  for (int i = 0; i < 9; ++i) {
    CaseRecord r;
    r.name = "p" + std::to_string(i);
    r.status = "ok";
    r.surface_mae_mm = 0.6 + 0.01 * i;
    r.time_s = 0.2;
    r.volume_right_ml = 400 + i;
    rs.push_back(r);
  }
  rs[4].surface_mae_mm = 3.0;  // far from the others
  CaseRecord bad;
  bad.name = "<bad & ugly>";
  bad.message = "scan.ply: truncated";
  rs.push_back(bad);
  return rs;
}

TEST(CohortHtml, Outliers) {
  const auto o = find_outliers(cohort());
  ASSERT_EQ(o.size(), 1u);  // time_s has MAD 0: no outliers there
  EXPECT_EQ(o[0].name, "p4");
  EXPECT_EQ(o[0].metric, "surface_mae_mm");
  EXPECT_GT(o[0].robust_z, 3);
  EXPECT_TRUE(find_outliers({}).empty());
}

TEST(CohortHtml, Page) {
  const std::string h = cohort_html(cohort());
  EXPECT_NE(h.find("10 cases: <b>9 ok</b>, 0 not usable, 1 failed"), std::string::npos);
  size_t svgs = 0;
  for (size_t p = h.find("<svg"); p != std::string::npos; p = h.find("<svg", p + 1)) ++svgs;
  EXPECT_EQ(svgs, 5u);
  EXPECT_NE(h.find("&lt;bad &amp; ugly&gt;"), std::string::npos);
  EXPECT_EQ(h.find("<bad & ugly>"), std::string::npos);
  EXPECT_NE(h.find("scan.ply: truncated"), std::string::npos);
  EXPECT_NE(h.find("<a href=\"p4/\">p4</a>"), std::string::npos);
  EXPECT_NE(h.find("no values"), std::string::npos);  // no landmark errors in this cohort
}

}  // namespace
}  // namespace breastfit::cohort
