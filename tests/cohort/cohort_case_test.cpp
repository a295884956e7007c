// What a CASE argument is: a scan file with a sibling landmark file, a case directory, a
// directory of cases; and the errors.
#include "breastfit/cohort/cohort_case.h"

#include <gtest/gtest.h>

#include <fstream>

#include "breastfit/core/errors.h"
#include "support/test_paths.h"

namespace breastfit::cohort {
namespace {

namespace fs = std::filesystem;

void touch(const fs::path& p) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << "x";
}

TEST(CohortCase, ScanFileWithSiblingLandmarks) {
  const fs::path d = test::temp_dir();
  touch(d / "p1.ply");
  touch(d / "p1.csv");
  touch(d / "p1.mrk.json");  // preferred over .csv
  touch(d / "p2.obj");
  const auto a = resolve_case_argument(d / "p1.ply");
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].name, "p1");
  EXPECT_EQ(a[0].scan, d / "p1.ply");
  ASSERT_TRUE(a[0].landmarks);
  EXPECT_EQ(*a[0].landmarks, d / "p1.mrk.json");
  const auto b = resolve_case_argument(d / "p2.obj");
  EXPECT_EQ(b[0].name, "p2");
  EXPECT_FALSE(b[0].landmarks);
}

TEST(CohortCase, CaseDirectoryAndDirectoryOfCases) {
  const fs::path d = test::temp_dir();
  touch(d / "cohort" / "b" / "scan.ply");
  touch(d / "cohort" / "b" / "landmarks.mrk.json");
  touch(d / "cohort" / "a" / "scan.stl");
  touch(d / "cohort" / "notes" / "readme.txt");  // no scan: not a case
  const auto one = resolve_case_argument(d / "cohort" / "b" / "");
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].name, "b");
  EXPECT_EQ(one[0].landmarks, d / "cohort" / "b" / "landmarks.mrk.json");
  const auto all = resolve_case_argument(d / "cohort");
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].name, "a");  // sorted
  EXPECT_EQ(all[0].scan, d / "cohort" / "a" / "scan.stl");
  EXPECT_FALSE(all[0].landmarks);
  EXPECT_EQ(all[1].name, "b");
}

TEST(CohortCase, Errors) {
  const fs::path d = test::temp_dir();
  touch(d / "notes.txt");
  touch(d / "x" / "scan.ply");
  touch(d / "y" / "x.ply");
  fs::create_directories(d / "empty");
  EXPECT_THROW(resolve_case_argument(d / "missing.ply"), IoError);
  EXPECT_THROW(resolve_case_argument(d / "notes.txt"), IoError);
  EXPECT_THROW(resolve_case_argument(d / "empty"), IoError);
  EXPECT_THROW(resolve_cases({}), InvalidInput);
  try {
    resolve_cases({d / "x", d / "y" / "x.ply"});
    FAIL() << "two cases named x";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("two cases named 'x'"), std::string::npos) << e.what();
  }
  // A directory of loose scan files is not a case (its scans are named one by one).
  EXPECT_THROW(resolve_cases({d / "x", d / "y"}), IoError);
}

}  // namespace
}  // namespace breastfit::cohort
