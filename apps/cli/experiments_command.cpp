// breastfit experiments --cases DIR --out DIR: the paper's experiments (Table 1, Figs 4–8, the
// resolution remark) on a directory of cases, with JSON, Markdown and PNG plots.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/core/timer.h"
#include "breastfit/experiments/case_set.h"
#include "breastfit/experiments/experiment_suite_json.h"
#include "breastfit/experiments/sweeps_markdown_json.h"
#include "breastfit/experiments/table1_markdown_json.h"
#include "breastfit/io/output_set.h"
#include "command_support.h"
#include "commands.h"
#include "exit_codes.h"

namespace breastfit::cli {
namespace {

namespace fs = std::filesystem;

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::vector<std::string> split_commas(const std::vector<std::string>& items) {
  std::vector<std::string> out;
  for (const auto& item : items) {
    std::stringstream s(item);
    std::string part;
    while (std::getline(s, part, ','))
      if (!part.empty()) out.push_back(part);
  }
  return out;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  if (!(f << text)) throw IoError(path.string(), "cannot be written");
}

/// Exit status of a shell command (-1 when it could not run).
int run_shell(const std::string& command) {
  const int status = std::system(command.c_str());
  if (status == -1) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Runs the experiments (and the referee) as the flags say; the JSON to write.
template <typename Args, typename Progress>
nlohmann::json run_suite(const Args& args, const Progress& progress, bool& referee_failed) {
  const fs::path out = args.out;
  const model::RiggedModel model = load_template(args.template_path);
  experiments::ExperimentOptions options =
      args.quick ? experiments::ExperimentOptions::quick() : experiments::ExperimentOptions{};
  options.fit = load_fit_options(args.config, args.fit);
  // The paper's experiments are about the paper's model: the surface-detail layer (which would
  // hide what blendshapes and λ do to the surface) only on request.
  if (!args.surface_detail) options.fit.detail.enabled = false;
  options.skip = split_commas(args.skip);
  options.template_cache_dir = out / "templates";
  if (!args.referee.empty()) {
    if (!fs::is_regular_file(args.referee)) throw IoError(args.referee, "no such referee script");
    options.contract_dir = out / "referee_results";
  }
  options.validate();
  const auto dirs = experiments::find_case_dirs(args.cases, split_commas(args.only));
  fs::create_directories(out);
  if (!options.contract_dir.empty()) fs::remove_all(options.contract_dir);

  nlohmann::json j = experiments::run_experiments(dirs, model, options, progress);
  j["config"]["cases_dir"] = fs::absolute(args.cases).string();
  j["config"]["quick"] = args.quick;
  j["config"]["template_file"] = args.template_path.empty() ? "(shipped default)" : args.template_path;

  if (!args.referee.empty()) {
    const fs::path rjson = out / "referee.json";
    fs::remove(rjson);
    // --cases may name one case folder: the referee wants the folder holding it.
    const fs::path cases_root = dirs.size() == 1 && fs::equivalent(dirs[0], args.cases)
                                    ? fs::weakly_canonical(dirs[0]).parent_path()
                                    : fs::path(args.cases);
    std::string cmd = shell_quote(args.python) + " " + shell_quote(args.referee) + " --cases " +
                      shell_quote(cases_root.string()) + " --results " + shell_quote(options.contract_dir.string()) +
                      " --json " + shell_quote(rjson.string()) + " --out " + shell_quote((out / "referee.md").string());
    cmd += " --only";
    for (const auto& d : dirs) cmd += " " + shell_quote(d.filename().string());
    progress("referee: " + cmd);
    Timer t;
    const int rc = run_shell(cmd + " > " + shell_quote((out / "referee.log").string()) + " 2>&1");
    nlohmann::json ref = {{"command", cmd}, {"exit_status", rc}, {"seconds", t.seconds()}};
    if (rc == 0 && fs::is_regular_file(rjson)) {
      std::ifstream f(rjson);
      ref["cases"] = nlohmann::json::parse(f)["cases"];
    } else {
      referee_failed = true;
      ref["error"] = "the referee failed (exit status " + std::to_string(rc) + "); see " + (out / "referee.log").string();
      std::fprintf(stderr, "breastfit: warning: %s\n", ref["error"].get<std::string>().c_str());
    }
    j["referee"] = ref;
  }
  return j;
}

}  // namespace

void register_experiments(CLI::App& app, int& exit_code) {
  struct Args {
    std::string cases, out, template_path, config, referee, python = "/usr/bin/python3";
    std::string plot_script = std::string(BREASTFIT_SOURCE_DIR) + "/experiments/plot.py";
    std::vector<std::string> only, skip;
    bool quick = false, no_plots = false, quiet = false, report_only = false, surface_detail = false;
    FitFlags fit;
  };
  auto args = std::make_shared<Args>();
  auto* sub = app.add_subcommand(
      "experiments",
      "Reproduce the paper's experiments on a directory of cases (bench layout): Table 1, landmarks (Fig. 4), "
      "blendshapes (Figs 5-6), λ sensitivity (Figs 7-8), template resolution; writes experiments.json, table1.md "
      "and PNG plots");
  sub->add_option("--cases", args->cases, "a directory of case folders (scan.ply, landmarks.mrk.json, truth/)");
  sub->add_option("--out,-o", args->out, "output directory (created; its files are replaced)")->required();
  sub->add_flag("--quick", args->quick,
                "reduced grids (landmarks 0/3/12, blendshapes 0/all, λ x 1/10 and 10, default resolution only)");
  sub->add_option("--only", args->only, "case ids to run (space or comma separated)");
  sub->add_option("--skip", args->skip, "experiments not to run: table1, landmarks, blendshapes, lambdas, resolution");
  sub->add_option("--template,-t", args->template_path, "rigged template (.glb/.gltf; default: the shipped one)");
  sub->add_option("--config", args->config, "JSON file with fit options (the default configuration)");
  sub->add_option("--referee", args->referee,
                  "the external referee (bench evaluate.py): scores the Table-1 fits, numbers stored alongside ours");
  sub->add_option("--python", args->python, "Python interpreter for the referee and the plots");
  sub->add_option("--plot-script", args->plot_script, "the plotting script");
  sub->add_flag("--no-plots", args->no_plots, "do not draw the PNG plots");
  sub->add_flag("--quiet,-q", args->quiet, "no progress lines");
  sub->add_flag("--report-only", args->report_only,
                "run nothing: rewrite table1.md, sweeps.md and the plots from OUT/experiments.json");
  sub->add_flag("--surface-detail", args->surface_detail,
                "also fit the surface-detail layer (default off: the paper's model, as in the paper)");
  add_fit_flags(*sub, args->fit);
  sub->callback([args, &exit_code] {
    Timer wall;
    const fs::path out = args->out;
    const auto progress = [quiet = args->quiet](const std::string& line) {
      if (!quiet) std::fprintf(stderr, "experiments: %s\n", line.c_str());
    };
    nlohmann::json j;
    bool referee_failed = false;
    size_t num_cases = 0;
    if (args->report_only) {
      const fs::path p = out / "experiments.json";
      std::ifstream f(p);
      if (!f) throw IoError(p.string(), "cannot be read (run the experiments first)");
      try {
        j = nlohmann::json::parse(f);
      } catch (const nlohmann::json::exception& e) {
        throw IoError(p.string(), std::string("not valid JSON: ") + e.what());
      }
      num_cases = j.value("cases", nlohmann::json::array()).size();
    } else {
      if (args->cases.empty()) throw CLI::RequiredError("--cases");
      j = run_suite(*args, progress, referee_failed);
      num_cases = j["cases"].size();
      j["command_wall_time_s_before_plots"] = wall.seconds();
    }
    // The tables and experiments.json as one set (io/output_set.h), experiments.json last.
    std::vector<fs::path> files = {out / "table1.md", out / "sweeps.md"};
    if (!args->report_only) files.push_back(out / "experiments.json");
    io::OutputSet set = io::loose_file_set(files);
    write_text(set.path("table1.md"), experiments::table1_markdown(j));
    write_text(set.path("sweeps.md"), experiments::sweeps_markdown(j));
    if (!args->report_only) write_text(set.path("experiments.json"), j.dump(1) + "\n");
    set.commit();

    std::string plots = "plots skipped (--no-plots)";
    if (!args->no_plots) {
      if (!fs::is_regular_file(args->python) && args->python.find('/') != std::string::npos) {
        plots = "plots skipped: no " + args->python;
      } else if (!fs::is_regular_file(args->plot_script)) {
        plots = "plots skipped: no plotting script " + args->plot_script;
      } else if (run_shell(shell_quote(args->python) + " -c 'import matplotlib' > /dev/null 2>&1") != 0) {
        plots = "plots skipped: " + args->python + " has no matplotlib (Debian: apt-get install python3-matplotlib)";
      } else {
        const std::string cmd = shell_quote(args->python) + " " + shell_quote(args->plot_script) + " " +
                                shell_quote((out / "experiments.json").string()) + " " + shell_quote(out.string());
        progress("plots: " + cmd);
        plots = run_shell(cmd) == 0 ? "plots written" : "plots FAILED (see the messages above)";
      }
    }
    std::printf("experiments: %zu cases in %.1f s; wrote %s, table1.md, sweeps.md; %s\n", num_cases, wall.seconds(),
                (out / "experiments.json").c_str(), plots.c_str());
    if (referee_failed) exit_code = kExitFailure;
  });
}

}  // namespace breastfit::cli
