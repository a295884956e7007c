// breastfit batch CASES... --out DIR [--jobs N]: a cohort on all cores of one machine — every case
// registered into DIR/<case>/, then DIR/cohort.csv and DIR/cohort.html; resumable.
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <thread>

#include "breastfit/cohort/batch.h"
#include "breastfit/core/timer.h"
#include "breastfit/model/template_library.h"
#include "breastfit/pipeline/provenance.h"
#include "command_support.h"
#include "commands.h"
#include "exit_codes.h"

namespace breastfit::cli {
namespace {

/// One line per finished case, or on a terminal a bar redrawn in place.
cohort::BatchProgress batch_progress(bool quiet) {
  if (quiet) return {};
  const bool tty = ::isatty(STDERR_FILENO) == 1;
  auto timer = std::make_shared<Timer>();
  auto counts = std::make_shared<std::array<int, 3>>();  // ok, not usable, failed
  return [tty, timer, counts](int done, int total, const cohort::CaseRecord& r) {
    (*counts)[r.status == "ok" ? 0 : r.status == "not_usable" ? 1 : 2]++;
    if (!tty) {
      std::fprintf(stderr, "breastfit batch: [%d/%d] %s %s%s%s\n", done, total, r.name.c_str(), r.status.c_str(),
                   r.resumed ? " (previous run)" : "", r.message.empty() ? "" : (": " + r.message).c_str());
      return;
    }
    constexpr int kWidth = 30;
    const int filled = total ? kWidth * done / total : kWidth;
    const double elapsed = timer->seconds();
    const double eta = done ? elapsed / done * (total - done) : 0;
    std::fprintf(stderr, "\r[%s%s] %d/%d  ok %d  not usable %d  failed %d  %.0f s left   ",
                 std::string(filled, '#').c_str(), std::string(kWidth - filled, '-').c_str(), done, total,
                 (*counts)[0], (*counts)[1], (*counts)[2], eta);
    if (done == total) std::fputc('\n', stderr);
    std::fflush(stderr);
  };
}

}  // namespace

void register_batch(CLI::App& app, int& exit_code) {
  struct Args {
    std::vector<std::string> cases;
    std::string out, template_path, units = "auto", config;
    int jobs = 0;
    bool force = false, quiet = false, no_landmarks = false, no_report_html = false;
    FitFlags fit;
  };
  auto args = std::make_shared<Args>();
  auto* sub = app.add_subcommand(
      "batch", "Register a cohort of scans on all cores: DIR/<case>/ with each case's outputs, DIR/cohort.csv and "
               "DIR/cohort.html; finished cases are skipped when run again (docs/COHORTS.md)");
  sub->add_option("cases", args->cases,
                  "a scan file (landmarks: the sibling <stem>.mrk.json/.json/.csv/.fcsv), a case directory "
                  "(scan.ply + landmarks.mrk.json) or a directory of case directories")
      ->required();
  sub->add_option("--out,-o", args->out, "output directory (created)")->required();
  sub->add_option("--jobs,-j", args->jobs, "cases registered at the same time (default 0: the number of cores)")
      ->check(CLI::Range(0, 1024));
  sub->add_option("--template,-t", args->template_path, "rigged template (.glb/.gltf); default: the shipped torso");
  sub->add_option("--units", args->units, "scan units: auto (from each scan's extent), mm or m")
      ->check(CLI::IsMember({"auto", "mm", "m"}));
  sub->add_option("--config", args->config, "JSON file with fit options (see docs/REGISTRATION.md)");
  sub->add_flag("--no-landmarks", args->no_landmarks, "ignore the landmark files: landmark-free fits");
  sub->add_flag("--force", args->force, "register every case again, even those a previous run finished");
  sub->add_flag("--no-report-html", args->no_report_html, "do not write each case's report.html");
  sub->add_flag("--quiet,-q", args->quiet, "no progress and no summary");
  add_fit_flags(*sub, args->fit);
  sub->callback([args, &exit_code] {
    std::vector<std::filesystem::path> arguments(args->cases.begin(), args->cases.end());
    const std::vector<cohort::CohortCase> cases = cohort::resolve_cases(arguments);
    cohort::BatchOptions options;
    options.jobs = args->jobs > 0 ? args->jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    options.run.model = std::make_shared<const model::RiggedModel>(load_template(args->template_path));
    options.run.template_path =
        args->template_path.empty() ? model::default_template_path() : std::filesystem::path(args->template_path);
    options.run.command_line = pipeline::shell_command_line(command_line());
    options.run.fit = load_fit_options(args->config, args->fit);
    options.run.units = parse_units_flag(args->units);
    options.run.ignore_landmarks = args->no_landmarks;
    options.run.force = args->force;
    options.run.report_html = !args->no_report_html;
    const auto records = cohort::run_batch(cases, args->out, options, batch_progress(args->quiet));
    cohort::write_cohort_summary(args->out, records);
    int ok = 0, resumed = 0;
    for (const auto& r : records) {
      ok += r.status == "ok";
      resumed += r.resumed;
    }
    if (!args->quiet)
      std::printf("%d cases: %d ok, %zu not ok (%d from a previous run); wrote %s/cohort.csv and cohort.html\n",
                  static_cast<int>(records.size()), ok, records.size() - ok, resumed, args->out.c_str());
    if (ok < static_cast<int>(records.size())) exit_code = kExitCasesFailed;
  });
}

}  // namespace breastfit::cli
