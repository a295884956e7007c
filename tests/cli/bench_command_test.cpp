// `breastfit bench` on a synthetic case made by `breastfit synth`: the table has the solver time
// and the whole run's time per case, their CPU times and their medians; --json prints every run (the table on stderr);
// the thread count and the load are reported and the threads do not change the fit; --refit
// moves a landmark by --refit-mm.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include <nlohmann/json.hpp>

#include "support/test_paths.h"
#include "support/toy_model.h"

namespace breastfit {
namespace {

namespace fs = std::filesystem;

TEST(BenchCommand, PrintsSolverAndWholeRunTimesPerCaseAndTheirMedians) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path tmp = test::temp_dir();  // (a second call would empty it)
  const fs::path cases = tmp / "cases";
  std::string out;
  ASSERT_EQ(test::run_cli("synth --quiet --seed 4 --out '" + (cases / "c4").string() + "'", &out), 0) << out;
  nlohmann::json runs[2];
  for (int threads : {1, 2}) {
    std::string json;  // --json: the numbers on stdout, the table on stderr
    ASSERT_EQ(test::run_cli_split("bench '" + cases.string() + "' -n 2 --threads " + std::to_string(threads) + " --json",
                                  &json, &out),
              0)
        << out;
    EXPECT_TRUE(std::regex_search(out, std::regex(R"(case\s+time_s\s+total_s\s+full_s\s+cpu_s\s+tot_cpu_s\s+full_cpu_s\s+iters)")))
        << out;
    EXPECT_TRUE(std::regex_search(
        out, std::regex(R"(c4\s+\d+\.\d+\s+\d+\.\d+\s+\d+\.\d+\s+\d+\.\d+\s+\d+\.\d+\s+\d+\.\d+\s+\d+\s+[\d.]+\s+[\d.]+\s+ok)")))
        << out;
    EXPECT_NE(out.find("(1 cases, 2 runs each, " + std::to_string(threads) + " threads, load average "),
              std::string::npos)
        << out;
    runs[threads - 1] = nlohmann::json::parse(json);
    const auto& c = runs[threads - 1]["cases"][0];
    ASSERT_EQ(c["time_s_all"].size(), 2u);
    ASSERT_EQ(c["total_s_all"].size(), 2u);
    ASSERT_EQ(c["full_s_all"].size(), 2u);
    ASSERT_EQ(c["cpu_s_all"].size(), 2u);
    ASSERT_EQ(c["total_cpu_s_all"].size(), 2u);
    ASSERT_EQ(c["full_cpu_s_all"].size(), 2u);
    // The whole run holds the solver's time and its CPU time the registration's; with report.html
    // it costs more CPU still (its wall time is a run of its own, on one fit thread beside the
    // report's layers: on a busy machine it need not be longer than the run without them).
    for (int k = 0; k < 2; ++k) {
      EXPECT_GT(c["total_s_all"][k].get<double>(), c["time_s_all"][k].get<double>());
      EXPECT_GT(c["full_s_all"][k].get<double>(), 0.0);
      EXPECT_GT(c["cpu_s_all"][k].get<double>(), 0.0);
      EXPECT_GE(c["total_cpu_s_all"][k].get<double>(), c["cpu_s_all"][k].get<double>());
      EXPECT_GT(c["full_cpu_s_all"][k].get<double>(), c["total_cpu_s_all"][k].get<double>());
    }
    // The phases of the time_s registrations: per case and their medians over the cases, each
    // phase no longer than the run (index build and fit within time_s, the rest within total_s).
    const auto& phases = c["phases_ms_median"];
    for (const char* phase : {"index_build", "initialization", "stage:shape", "stage:refine", "landmark_checks",
                              "transfer", "measurements"}) {
      ASSERT_TRUE(phases.contains(phase)) << phase << " in " << phases.dump();
      EXPECT_GT(phases[phase].get<double>(), 0.0) << phase;
      EXPECT_EQ(runs[threads - 1]["median_phases_ms"][phase], phases[phase]) << phase;  // one case
    }
    EXPECT_LT(phases["index_build"].get<double>() + phases["stage:shape"].get<double>(),
              1000.0 * c["time_s_median"].get<double>());
    EXPECT_NE(out.find("phases of the time_s registrations, ms (median over cases of the per-case medians): "),
              std::string::npos)
        << out;
    EXPECT_TRUE(std::regex_search(out, std::regex(R"(index_build \d+\.\d, .* stage:shape \d+\.\d,)"))) << out;
    EXPECT_TRUE(runs[threads - 1]["load_average"].is_number());
    EXPECT_EQ(runs[threads - 1]["threads"], threads);
  }
  // Same fit whatever the thread count.
  EXPECT_EQ(runs[0]["cases"][0]["surface_mae_mm"], runs[1]["cases"][0]["surface_mae_mm"]);
  EXPECT_EQ(runs[0]["cases"][0]["iterations"], runs[1]["cases"][0]["iterations"]);
}

// --suggest: the workstation's Suggest timed per case (server time, wall and CPU), every run in the JSON.
TEST(BenchCommand, TimesTheWorkstationsSuggest) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path tmp = test::temp_dir();
  const fs::path cases = tmp / "cases";
  std::string out;
  ASSERT_EQ(test::run_cli("synth --quiet --seed 6 --out '" + (cases / "c6").string() + "'", &out), 0) << out;
  std::string json;
  ASSERT_EQ(test::run_cli_split("bench '" + cases.string() + "' --suggest -n 2 --json", &json, &out), 0) << out;
  EXPECT_TRUE(std::regex_search(out, std::regex(R"(case\s+suggest_ms_med\s+suggest_ms_max\s+cpu_ms_med)"))) << out;
  EXPECT_TRUE(std::regex_search(out, std::regex(R"(c6\s+[\d.]+\s+[\d.]+\s+[\d.]+\s+ok)"))) << out;
  EXPECT_NE(out.find("suggest, median of all 2:"), std::string::npos) << out;
  const auto j = nlohmann::json::parse(json);
  ASSERT_EQ(j["cases"][0]["suggest_ms_all"].size(), 2u);
  EXPECT_GT(j["median_suggest_ms"].get<double>(), 0.0);
  EXPECT_NE(test::run_cli("bench '" + cases.string() + "' --suggest --refit", &out), 0) << out;
}

TEST(BenchCommand, RejectsANegativeThreadCount) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  std::string out;
  EXPECT_EQ(test::run_cli("bench '" + test::temp_dir().string() + "' --threads -1", &out), 2) << out;
}

TEST(BenchCommand, MeshChoosesOneSkinnedMeshOfATemplate) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path tmp = test::temp_dir();
  const fs::path two = test::save_two_mesh_toy(tmp);
  std::string out;
  ASSERT_EQ(test::run_cli("synth --quiet --holes 0 --seed 4 --template '" + two.string() + "' --mesh First --out '" +
                              (tmp / "cases" / "c1").string() + "'",
                          &out),
            0)
      << out;
  const std::string common = "bench '" + (tmp / "cases").string() + "' -n 1 --template '" + two.string() + "'";
  EXPECT_EQ(test::run_cli(common, &out), 4) << out;
  EXPECT_NE(out.find("choose one with --mesh NAME"), std::string::npos) << out;
  ASSERT_EQ(test::run_cli(common + " --mesh Second", &out), 0) << out;
  EXPECT_TRUE(std::regex_search(out, std::regex(R"(c1\s+\d+\.\d+)"))) << out;
}

TEST(BenchCommand, RefitMovesALandmarkByTheAskedDistance) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path tmp = test::temp_dir();
  const fs::path cases = tmp / "cases";
  std::string out;
  ASSERT_EQ(test::run_cli("synth --quiet --seed 5 --out '" + (cases / "c5").string() + "'", &out), 0) << out;
  std::string json;
  ASSERT_EQ(test::run_cli_split("bench '" + cases.string() + "' --refit --refit-mm 6 -n 2 --threads 1 --json", &json, &out), 0)
      << out;
  EXPECT_NE(out.find("re-fit after a 6.0 mm move, median of all 2:"), std::string::npos) << out;
  const auto j = nlohmann::json::parse(json);
  EXPECT_EQ(j["move_mm"], 6.0);
  EXPECT_EQ(j["cases"][0]["refit_ms_all"].size(), 2u);
  EXPECT_EQ(j["cases"][0]["usable"], true);
  // A negative distance is refused as a usage error.
  EXPECT_EQ(test::run_cli("bench '" + cases.string() + "' --refit --refit-mm -1", &out), 2) << out;
}

}  // namespace
}  // namespace breastfit
