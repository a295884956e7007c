// `breastfit synth` end to end: the bench case layout, alternating poses, refusal to overwrite,
// one-line errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "breastfit/model/gltf_io.h"
#include "support/test_paths.h"
#include "support/toy_model.h"

namespace breastfit {
namespace {

namespace fs = std::filesystem;

/// The toy model saved as a template file (the CLI's --template), once per test.
fs::path toy_template(const fs::path& dir) {
  const fs::path p = dir / "toy.glb";
  model::save_gltf(p, test::make_toy_model());
  return p;
}

const char* kToyFlags = " --quiet --fragments 2 --holes 0";

TEST(SynthCommand, WritesOneCaseInTheBenchLayout) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  const fs::path tpl = toy_template(dir);
  const fs::path out = dir / "case1";
  std::string log;
  ASSERT_EQ(test::run_cli("synth --out '" + out.string() + "' --seed 4 --units m --template '" + tpl.string() + "'" +
                              kToyFlags,
                          &log),
            0)
      << log;
  for (const char* f : {"scan.ply", "landmarks.mrk.json", "truth/surface.ply", "truth/landmarks.json",
                        "truth/curves.json", "truth/landmarks.mrk.json", "truth/meta.json"})
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
  const auto meta = nlohmann::json::parse(test::file_bytes(out / "truth/meta.json"));
  EXPECT_EQ(meta["units"], "m");
  EXPECT_EQ(meta["id"], "case1");
  EXPECT_EQ(meta["seed"].get<int>(), 4);
  EXPECT_EQ(meta["pose"]["type"], "standing");
  EXPECT_EQ(meta["scan_params"]["n_holes"].get<int>(), 0);

  // Existing case: refused without --force (I/O error, one line), replaced with it.
  ASSERT_EQ(test::run_cli("synth --out '" + out.string() + "' --seed 5 --template '" + tpl.string() + "'" + kToyFlags,
                          &log),
            4)
      << log;
  EXPECT_NE(log.find("breastfit: error:"), std::string::npos) << log;
  EXPECT_NE(log.find("--force"), std::string::npos) << log;
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;
  ASSERT_EQ(test::run_cli("synth --out '" + out.string() + "' --seed 5 --force --template '" + tpl.string() + "'" +
                              kToyFlags,
                          &log),
            0)
      << log;
  EXPECT_EQ(nlohmann::json::parse(test::file_bytes(out / "truth/meta.json"))["seed"].get<int>(), 5);
}

TEST(SynthCommand, CountAlternatesPoses) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  const fs::path tpl = toy_template(dir);
  std::string log;
  ASSERT_EQ(test::run_cli("synth --out '" + (dir / "set").string() + "' --count 2 --seed 7 --template '" +
                              tpl.string() + "'" + kToyFlags,
                          &log),
            0)
      << log;
  const auto a = nlohmann::json::parse(test::file_bytes(dir / "set/synth_007_standing/truth/meta.json"));
  const auto b = nlohmann::json::parse(test::file_bytes(dir / "set/synth_008_supine/truth/meta.json"));
  EXPECT_EQ(a["pose"]["type"], "standing");
  EXPECT_EQ(b["pose"]["type"], "supine");
  EXPECT_EQ(b["seed"].get<int>(), 8);
}

TEST(SynthCommand, BadValuesGiveOneLineErrors) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  std::string log;
  EXPECT_EQ(test::run_cli("synth --out '" + (dir / "x").string() + "' --pose prone", &log), 3) << log;
  EXPECT_NE(log.find("prone"), std::string::npos) << log;
  EXPECT_EQ(test::run_cli("synth --out '" + (dir / "x").string() + "' --units cm", &log), 3) << log;
  EXPECT_NE(log.find("units"), std::string::npos) << log;
  EXPECT_EQ(test::run_cli("synth --out '" + (dir / "x").string() + "' --noise-mm -1", &log), 3) << log;
  EXPECT_EQ(test::run_cli("synth --out '" + (dir / "x").string() + "' --template '" + (dir / "none.glb").string() + "'",
                          &log),
            4)
      << log;
  EXPECT_FALSE(fs::exists(dir / "x" / "scan.ply"));
}

TEST(SynthCommand, MeshChoosesOneSkinnedMeshOfATemplate) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  const fs::path two = test::save_two_mesh_toy(dir);
  std::string log;
  const std::string common = "synth --seed 4 --template '" + two.string() + "'" + kToyFlags;
  EXPECT_EQ(test::run_cli(common + " --out '" + (dir / "a").string() + "'", &log), 4) << log;
  EXPECT_NE(log.find("choose one with --mesh NAME"), std::string::npos) << log;
  ASSERT_EQ(test::run_cli(common + " --mesh Second --out '" + (dir / "b").string() + "'", &log), 0) << log;
  EXPECT_TRUE(fs::is_regular_file(dir / "b" / "truth" / "meta.json"));
}

}  // namespace
}  // namespace breastfit
