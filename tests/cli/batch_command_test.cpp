// `breastfit batch` end to end: a good case and a bad one (exit 6, cohort.csv/.html), resumed,
// progress lines when stderr is not a terminal, argument errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/test_paths.h"

namespace breastfit {
namespace {

namespace fs = std::filesystem;

TEST(BatchCommand, GoodAndBadCaseThenResumed) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  ASSERT_EQ(test::run_cli("synth --out '" + (dir / "good").string() + "' --seed 5 --quiet"), 0);
  std::ofstream(dir / "bad.obj") << "v 0 0 0\nf 1 2 3\n";
  const std::string cmd = "batch '" + (dir / "good").string() + "' '" + (dir / "bad.obj").string() + "' --out '" +
                          (dir / "out").string() + "' --jobs 2 --no-report-html";
  std::string out;
  EXPECT_EQ(test::run_cli(cmd, &out), 6) << out;
  EXPECT_NE(out.find("breastfit batch: [2/2]"), std::string::npos) << out;  // not a terminal: lines, no bar
  EXPECT_EQ(out.find('\r'), std::string::npos);
  EXPECT_NE(out.find("2 cases: 1 ok, 1 not ok (0 from a previous run)"), std::string::npos) << out;
  const std::string csv = test::file_bytes(dir / "out" / "cohort.csv");
  EXPECT_NE(csv.find("\ngood,ok,no,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\nbad,failed,no,"), std::string::npos) << csv;
  EXPECT_TRUE(fs::exists(dir / "out" / "good" / "params.json"));
  EXPECT_NE(test::file_bytes(dir / "out" / "cohort.html").find("<svg"), std::string::npos);

  EXPECT_EQ(test::run_cli(cmd + " --quiet", &out), 6) << out;
  EXPECT_TRUE(out.empty()) << out;
  EXPECT_NE(test::file_bytes(dir / "out" / "cohort.csv").find("\ngood,ok,yes,"), std::string::npos);
}

TEST(BatchCommand, ArgumentErrors) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  std::string out;
  EXPECT_EQ(test::run_cli("batch '" + (dir / "none").string() + "' --out '" + (dir / "o").string() + "'", &out), 4);
  EXPECT_NE(out.find("none: no such file or directory"), std::string::npos) << out;
  EXPECT_EQ(test::run_cli("batch x.ply", &out), 2) << out;  // --out is required
  EXPECT_EQ(test::run_cli("batch x.ply --out o --jobs -1", &out), 2) << out;
}

}  // namespace
}  // namespace breastfit
