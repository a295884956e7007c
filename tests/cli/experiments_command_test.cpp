// `breastfit experiments` end to end on one synthetic case (made by `breastfit synth`): the
// reduced suite writes experiments.json, table1.md and, when Debian's matplotlib is present,
// the PNG plots of experiments/plot.py; bad command lines are refused with the documented codes.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "support/test_paths.h"

namespace breastfit {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

bool have_matplotlib() {
  return fs::exists("/usr/bin/python3") &&
         std::system("/usr/bin/python3 -c 'import matplotlib' > /dev/null 2>&1") == 0;
}

TEST(ExperimentsCommand, QuickRunWritesJsonTableAndPlots) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  std::string log;
  ASSERT_EQ(test::run_cli("synth --out '" + (dir / "cases" / "synth_021_standing").string() + "' --seed 21 --quiet", &log), 0)
      << log;
  const fs::path out = dir / "out";
  ASSERT_EQ(test::run_cli("experiments --cases '" + (dir / "cases").string() + "' --out '" + out.string() +
                              "' --quick --skip lambdas,resolution",
                          &log),
            0)
      << log;
  EXPECT_NE(log.find("experiments: [1/1]"), std::string::npos) << log;  // progress lines
  const auto j = nlohmann::json::parse(read_text(out / "experiments.json"));
  EXPECT_EQ(j["cases"].size(), 1u);
  EXPECT_EQ(j["table1"]["runs"].size(), 1u);
  EXPECT_EQ(j["landmarks"]["runs"].size(), 3u);
  EXPECT_EQ(j["blendshapes"]["runs"].size(), 2u);
  EXPECT_FALSE(j.contains("lambdas"));
  EXPECT_FALSE(j.contains("resolution"));
  EXPECT_TRUE(j["config"]["quick"].get<bool>());
  EXPECT_NE(read_text(out / "sweeps.md").find("## Fig. 4"), std::string::npos);
  const std::string md = read_text(out / "table1.md");
  EXPECT_NE(md.find("synth_021_standing"), std::string::npos) << md;
  if (have_matplotlib()) {
    for (const char* png : {"fig4_landmarks.png", "fig5_blendshapes_standing.png"})
      EXPECT_GT(fs::file_size(out / png), 10000u) << png << "\n" << log;
    EXPECT_FALSE(fs::exists(out / "fig6_blendshapes_supine.png"));  // no supine case
  } else {
    EXPECT_NE(log.find("plots skipped"), std::string::npos) << log;
  }
  fs::remove_all(dir);
}

TEST(ExperimentsCommand, RefusesBadCommandLines) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  std::string log;
  EXPECT_EQ(test::run_cli("experiments --cases '" + dir.string() + "'", &log), 2) << log;  // no --out
  EXPECT_EQ(test::run_cli("experiments --cases '" + (dir / "missing").string() + "' --out '" + (dir / "o").string() + "'",
                          &log),
            4)
      << log;
  EXPECT_NE(log.find("not a directory"), std::string::npos) << log;
  fs::create_directories(dir / "empty");
  EXPECT_EQ(test::run_cli("experiments --cases '" + (dir / "empty").string() + "' --out '" + (dir / "o").string() + "'",
                          &log),
            4)
      << log;
  EXPECT_EQ(test::run_cli("experiments --cases '" + (dir / "empty").string() + "' --out '" + (dir / "o").string() +
                              "' --skip nonsense",
                          &log),
            3)
      << log;
  EXPECT_NE(log.find("unknown experiment 'nonsense'"), std::string::npos) << log;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace breastfit
