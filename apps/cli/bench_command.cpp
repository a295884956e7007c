// breastfit bench DIR: registration timings (medians) over a directory of cases: the solver's
// time (time_s: scan and landmarks in memory → fitted parameters) and the whole register run
// (total_s: reading the scan and landmarks, the registration with transfer and measurements, and
// writing the outputs without report.html, as `register --no-report-html` does) and the default
// `register` run end to end (full_s: a second registration as `register` runs it: reading, the
// report's scan layers drawn beside the fit, then all the outputs with report.html, which is
// rendered while the others are written), with CPU
// times (cpu_s: the register_scan call; tot_cpu_s: the whole run without report.html;
// full_cpu_s: with it), as the machine may be busy.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <iostream>
#include <time.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/core/timer.h"
#include "breastfit/experiments/case_set.h"
#include "breastfit/fit/fit_summary.h"
#include "breastfit/fit/parallel_chunks.h"
#include "breastfit/io/io.h"
#include "breastfit/io/landmarks_io.h"
#include "breastfit/pipeline/fit_deviation.h"
#include "breastfit/pipeline/register_outputs.h"
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/pipeline/report_html.h"
#include "breastfit/pipeline/report_layers.h"
#include "breastfit/serve/scan_session.h"
#include "command_support.h"
#include "commands.h"

namespace breastfit::cli {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A registration's phase times in ms by name (RegisterResult::timings); a phase listed twice (the
// refine stage again after a flagged landmark) counts both runs, as in report.json's timings_s.
std::map<std::string, double> phase_ms(const std::vector<fit::PhaseTime>& timings) {
  std::map<std::string, double> out;
  for (const auto& t : timings) out[t.phase] += 1000.0 * t.seconds;
  return out;
}

// CPU seconds of the whole process so far (every thread; OpenMP's waiting threads spin, so with
// 2 threads on a busy machine this exceeds the work done).
double process_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// The re-fits' deviations (pipeline::fit_deviation) from the same re-fits with the whole refine
// stage (RefitOptions off: its full threshold schedule and cap, no vertex tolerance), and from
// full fits from scratch with the same moved landmarks.
struct RefitDeviations {
  std::vector<pipeline::FitDeviation> full_refine, cold;
};

// The workstation's Re-fit: the scan opened once (serve::ScanSession), a full fit, then `repeat`
// warm-started re-fits, each after moving one landmark (in turn) by `move_mm` along the scan's x,
// y or z.
// Returns the server time of each re-fit, ms (fit, transfer, measurements, distances): wall and
// the thread's CPU time (the work is single-threaded: CPU time is the wall time without the
// machine's other load); `first_ms` and `first_cpu_ms` the same to the re-fit's first result (the
// fitted model and drawings the page shows before the landmark checks, distances and measurements:
// serve::FitOutcome::surface_ms). With `deviations` (--compare-cold), each re-fit is also run with the whole refine stage (a
// session of its own, re-fitted in the same order) and fitted from scratch; `phases_ms` collects
// the re-fits' phase times (RegisterResult::timings) by name.
std::vector<double> time_refits(const std::filesystem::path& dir, const std::shared_ptr<const model::RiggedModel>& model,
                                const fit::FitOptions& options, int repeat, double move_mm, bool& usable,
                                std::vector<double>& cpu_ms, std::vector<double>& first_ms, std::vector<double>& first_cpu_ms,
                                std::map<std::string, std::vector<double>>& phases_ms,
                                std::vector<double>& iterations, RefitDeviations* deviations) {
  const std::string scan_name = (dir / "scan.ply").string();
  serve::ScanSession session("bench", dir / "scan.ply", scan_name, model, options);
  std::unique_ptr<serve::ScanSession> slow, cold;
  if (deviations) {
    fit::FitOptions whole = options;
    whole.refit.final_threshold = false;
    whole.refit.max_iterations = options.refine.max_iterations;
    whole.refit.vertex_tolerance_mm = 0;
    slow = std::make_unique<serve::ScanSession>("full refine", dir / "scan.ply", scan_name, model, whole);
    cold = std::make_unique<serve::ScanSession>("cold", dir / "scan.ply", scan_name, model, options);
  }
  LandmarkSet lms = io::landmarks_to_mm(io::read_landmarks(dir / "landmarks.mrk.json"), session.scan().units);
  lms.declared_units = "mm";
  usable = session.run_fit(lms, false)->result.usable();
  if (slow) slow->run_fit(lms, false);
  std::vector<double> ms;
  for (int k = 0; k < repeat && usable; ++k) {
    LandmarkSet moved = lms;
    moved.points[k % moved.points.size()].position[k % 3] += move_mm;
    const auto outcome = session.run_fit(moved, true);
    if (!outcome->warm) throw InvalidInput(dir.string() + ": the re-fit was not warm-started");
    usable = usable && outcome->result.usable();
    ms.push_back(outcome->server_ms);
    cpu_ms.push_back(outcome->server_cpu_ms);
    first_ms.push_back(outcome->surface_ms);
    first_cpu_ms.push_back(outcome->surface_cpu_ms);
    iterations.push_back(static_cast<double>(outcome->result.fit.summary.iterations.size()));
    for (const auto& [phase, ms_of_phase] : phase_ms(outcome->result.timings))
      if (phase != "scan_preparation" && phase != "index_build") phases_ms[phase].push_back(ms_of_phase);
    if (deviations && outcome->result.usable()) {
      const auto whole = slow->run_fit(moved, true);
      if (whole->result.usable()) deviations->full_refine.push_back(pipeline::fit_deviation(outcome->result, whole->result));
      const auto full = cold->run_fit(moved, false);
      if (full->result.usable()) deviations->cold.push_back(pipeline::fit_deviation(outcome->result, full->result));
    }
  }
  return ms;
}

// The workstation's Suggest: the scan opened once, then `repeat` landmark suggestions
// (serve::ScanSession::run_suggest: a landmark-free fit, the landmarks snapped to the scan).
// Returns each one's server time, ms, wall and CPU as time_refits.
std::vector<double> time_suggests(const std::filesystem::path& dir, const std::shared_ptr<const model::RiggedModel>& model,
                                  const fit::FitOptions& options, int repeat, bool& usable, std::vector<double>& cpu_ms) {
  serve::ScanSession session("bench", dir / "scan.ply", (dir / "scan.ply").string(), model, options);
  std::vector<double> ms;
  usable = true;
  for (int k = 0; k < repeat && usable; ++k) {
    try {
      const auto outcome = session.run_suggest();
      ms.push_back(outcome->server_ms);
      cpu_ms.push_back(outcome->server_cpu_ms);
    } catch (const InvalidInput&) {
      usable = false;  // the landmark-free fit is not usable
    }
  }
  return ms;
}

// Deviations of the re-fits from `what`: median and largest over the re-fits of each measure.
void print_deviations(FILE* text, const std::string& what, const std::vector<pipeline::FitDeviation>& d) {
  auto row = [&](const char* what, double pipeline::FitDeviation::*field) {
    std::vector<double> v;
    for (const auto& x : d) v.push_back(x.*field);
    std::fprintf(text, "  %-28s median %.3f mm, max %.3f mm\n", what, median(v), v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()));
  };
  std::fprintf(text, "re-fit vs %s (%zu pairs, both usable):\n", what.c_str(), d.size());
  row("surface, median vertex", &pipeline::FitDeviation::surface_median_mm);
  row("surface, farthest vertex", &pipeline::FitDeviation::surface_max_mm);
  row("landmarks, farthest", &pipeline::FitDeviation::landmarks_max_mm);
  row("drawings, farthest point", &pipeline::FitDeviation::drawings_max_mm);
}

}  // namespace

void register_bench(CLI::App& app, int& exit_code) {
  struct Args {
    std::string dir, template_path, template_mesh, config;
    int repeat = 5;
    double refit_mm = 10.0;
    bool no_landmarks = false, refit = false, suggest = false, compare_cold = false, json = false;
    FitFlags fit;
  };
  auto args = std::make_shared<Args>();
  auto* sub = app.add_subcommand("bench", "Time the registration on case directories (scan.ply + "
                                          "landmarks.mrk.json) and print medians: time_s (scan in memory -> "
                                          "fitted parameters), total_s (read, register, write the outputs without report.html, as "
                                          "register --no-report-html) and full_s (read, register, write all the outputs with report.html: "
                                          "the default register end to end, in this process), each with its CPU time (cpu_s, tot_cpu_s, full_cpu_s)");
  sub->add_option("dir", args->dir, "a case directory or a directory of them")->required();
  sub->add_option("--repeat,-n", args->repeat, "registrations per case (the median is reported)")
      ->check(CLI::Range(1, 100));
  sub->add_flag("--no-landmarks", args->no_landmarks, "landmark-free registration");
  sub->add_flag("--refit", args->refit,
                "time the workstation's warm-started re-fit after moving one landmark (server time, ms)");
  sub->add_option("--refit-mm", args->refit_mm, "how far --refit moves the landmark, mm (default 10)")
      ->check(CLI::Range(0.0, 200.0));
  sub->add_flag("--compare-cold", args->compare_cold,
                "with --refit: also re-fit each moved landmark set with the whole refine stage and fit it from "
                "scratch, and print how far the re-fits lie from those (surface, landmarks, drawings, mm)");
  sub->add_flag("--suggest", args->suggest,
                "time the workstation's Suggest: the 12 landmarks found on the open scan (server time, ms)");
  sub->add_option("--template,-t", args->template_path, "rigged template (.glb/.gltf)");
  sub->add_option("--mesh", args->template_mesh, "the template's skinned mesh to use when its file has several (node or mesh name)");
  sub->add_option("--config", args->config, "JSON file with fit options");
  sub->add_flag("--json", args->json,
                "print every number as JSON on stdout (the table goes to stderr; as every --json: redirect it to keep it)");
  add_fit_flags(*sub, args->fit);
  sub->callback([args, &exit_code] {
    FILE* text = args->json ? stderr : stdout;  // the table; stdout is the JSON's with --json
    if (args->refit && args->suggest) throw InvalidInput("bench: --refit and --suggest time different things: choose one");
    const auto model = std::make_shared<const model::RiggedModel>(load_template(args->template_path, args->template_mesh));
    auto options = load_fit_options(args->config, args->fit);
    if (args->no_landmarks) options.use_landmarks = false;
    nlohmann::json cases = nlohmann::json::array();
    std::vector<double> medians, total_medians, full_medians;
    if (args->refit || args->suggest) {
      const std::string job = args->suggest ? "suggest" : "refit";
      if (args->compare_cold && !args->refit) throw InvalidInput("bench: --compare-cold needs --refit");
      std::vector<double> all, all_cpu, cpu_medians, all_first, all_first_cpu;
      std::map<std::string, std::vector<double>> phases_ms;
      std::vector<double> iterations;
      RefitDeviations deviations;
      std::fprintf(text, "%-24s %12s %12s %12s %8s\n", "case", (job + "_ms_med").c_str(), (job + "_ms_max").c_str(), "cpu_ms_med",
                  "status");
      for (const auto& dir : experiments::find_case_dirs(args->dir)) {
        bool usable = false;
        std::vector<double> cpu, first, first_cpu;
        const std::vector<double> ms =
            args->suggest ? time_suggests(dir, model, options, args->repeat, usable, cpu)
                          : time_refits(dir, model, options, args->repeat, args->refit_mm, usable, cpu, first,
                                        first_cpu, phases_ms, iterations, args->compare_cold ? &deviations : nullptr);
        all_first.insert(all_first.end(), first.begin(), first.end());
        all_first_cpu.insert(all_first_cpu.end(), first_cpu.begin(), first_cpu.end());
        all.insert(all.end(), ms.begin(), ms.end());
        all_cpu.insert(all_cpu.end(), cpu.begin(), cpu.end());
        medians.push_back(median(ms));
        cpu_medians.push_back(median(cpu));
        std::fprintf(text, "%-24s %12.1f %12.1f %12.1f %8s\n", dir.filename().string().c_str(), median(ms),
                    ms.empty() ? 0.0 : *std::max_element(ms.begin(), ms.end()), median(cpu), usable ? "ok" : "FAILED");
        cases.push_back({{"case", dir.filename().string()}, {job + "_ms_median", median(ms)}, {job + "_ms_all", ms},
                         {job + "_cpu_ms_median", median(cpu)}, {job + "_cpu_ms_all", cpu}, {"usable", usable}});
        if (args->refit) {
          cases.back()["first_result_ms_all"] = first;
          cases.back()["first_result_cpu_ms_all"] = first_cpu;
        }
      }
      char what[64] = "suggest";
      if (!args->suggest) std::snprintf(what, sizeof what, "re-fit after a %.1f mm move", args->refit_mm);
      std::fprintf(text, "%s, median of all %zu: %.1f ms wall, %.1f ms CPU (median of the case medians: %.1f ms wall, "
                  "%.1f ms CPU)\n",
                  what, all.size(), median(all), median(all_cpu), median(medians), median(cpu_medians));
      if (args->refit)
        std::fprintf(text, "re-fit's first result (the fitted model and drawings; the landmark checks, distances and "
                    "measurements follow), median of all %zu: %.1f ms wall, %.1f ms CPU\n",
                    all_first.size(), median(all_first), median(all_first_cpu));
      if (!phases_ms.empty()) {
        std::fprintf(text, "re-fits: median %.1f iterations; phases (median ms, wall):", median(iterations));
        for (const auto& [phase, v] : phases_ms) std::fprintf(text, " %s %.1f", phase.c_str(), median(v));
        std::fprintf(text, "\n");
      }
      if (args->compare_cold) {
        print_deviations(text, "the same re-fit with the whole refine stage", deviations.full_refine);
        print_deviations(text, "a full fit from scratch with the same landmarks", deviations.cold);
      }
      if (args->json) {
        nlohmann::json j{{"cases", cases}, {"median_" + job + "_ms", median(all)}, {"median_" + job + "_cpu_ms", median(all_cpu)},
                         {"repeat", args->repeat}};
        if (args->refit) {
          j["move_mm"] = args->refit_mm;
          j["median_first_result_ms"] = median(all_first);
          j["median_first_result_cpu_ms"] = median(all_first_cpu);
        }
        std::cout << j.dump(1) << "\n";
      }
      return;
    }
    // The outputs of every run go to one scratch directory, removed at the end.
    const std::filesystem::path scratch =
        std::filesystem::temp_directory_path() / ("breastfit-bench-" + std::to_string(::getpid()));
    pipeline::RegisterOutputOptions output_options;
    output_options.report_html = false;
    const pipeline::RegisterOutputOptions full_options;  // the default: with report.html
    std::fprintf(text, "%-24s %9s %9s %9s %9s %9s %10s %6s %10s %10s %8s\n", "case", "time_s", "total_s", "full_s", "cpu_s",
                "tot_cpu_s", "full_cpu_s", "iters", "surf_mae", "lm_mae", "status");
    std::vector<double> cpu_medians, total_cpu_medians, full_cpu_medians;
    // The phases of the time_s registrations (report.json's timings_s: index build, the fit's
    // stages and checks, transfer, measurements), in the order they first ran; per case the median
    // over its runs, then the median over the cases.
    std::vector<std::string> phase_order;
    std::map<std::string, std::vector<double>> phase_case_medians;
    for (const auto& dir : experiments::find_case_dirs(args->dir)) {
      std::vector<double> times, totals, fulls, cpus, total_cpus, full_cpus;
      std::map<std::string, std::vector<double>> phase_runs;
      pipeline::RegisterResult last;
      auto read_request = [&] {
        pipeline::RegisterRequest req;
        req.scan = io::read_mesh(dir / "scan.ply");
        req.scan_name = (dir / "scan.ply").string();
        req.model = model;
        req.options = options;
        if (!args->no_landmarks && std::filesystem::exists(dir / "landmarks.mrk.json"))
          req.landmarks = io::read_landmarks(dir / "landmarks.mrk.json");
        return req;
      };
      for (int k = 0; k < args->repeat; ++k) {
        Timer total;
        const double cpu_start = process_cpu_s();
        const pipeline::RegisterRequest req = read_request();
        const double cpu_register = process_cpu_s();
        last = pipeline::register_scan(req);
        cpus.push_back(process_cpu_s() - cpu_register);
        const double registered_s = total.seconds(), registered_cpu = process_cpu_s() - cpu_start;
        times.push_back(last.time_s);
        for (const auto& t : last.timings)
          if (std::find(phase_order.begin(), phase_order.end(), t.phase) == phase_order.end()) phase_order.push_back(t.phase);
        for (const auto& [phase, ms] : phase_ms(last.timings)) phase_runs[phase].push_back(ms);
        Timer outputs;
        const double cpu_outputs = process_cpu_s();
        if (last.usable()) pipeline::write_register_outputs(scratch, last, *model, true, {}, output_options);
        totals.push_back(registered_s + outputs.seconds());
        total_cpus.push_back(registered_cpu + process_cpu_s() - cpu_outputs);
        // The default `register` once more as it runs (full_s): the report's scan layers drawn
        // beside the fit, then every output with report.html (made while the others are written).
        Timer full;
        const double cpu_full = process_cpu_s();
        pipeline::RegisterRequest full_req = read_request();
        full_req.options.threads = pipeline::fit_threads_beside_layers(full_req.landmarks, full_req.options);  // as register
        pipeline::RegisterOutputOptions with_layers = full_options;
        pipeline::PreparedTarget target = pipeline::prepare_target(
            full_req.scan, full_req.scan_name, {}, full_req.options, [&](const pipeline::PreparedScan& scan) {
              with_layers.layers = pipeline::start_report_layers(scan, full_req.landmarks, full_req.options,
                                                                 [m = full_req.model] { return m; }, full_options.figures);
            });
        const pipeline::RegisterResult full_result = pipeline::register_prepared(full_req, target);
        if (full_result.usable()) pipeline::write_register_outputs(scratch, full_result, *model, true, {}, with_layers);
        fulls.push_back(full.seconds());
        full_cpus.push_back(process_cpu_s() - cpu_full);
      }
      const double med = median(times), total_med = median(totals), full_med = median(fulls);
      medians.push_back(med);
      total_medians.push_back(total_med);
      full_medians.push_back(full_med);
      cpu_medians.push_back(median(cpus));
      total_cpu_medians.push_back(median(total_cpus));
      full_cpu_medians.push_back(median(full_cpus));
      std::fprintf(text, "%-24s %9.4f %9.4f %9.4f %9.4f %9.4f %10.4f %6zu %10.3f %10.3f %8s\n", dir.filename().string().c_str(),
                  med, total_med, full_med, median(cpus), median(total_cpus), median(full_cpus),
                  last.fit.summary.iterations.size(),
                  last.surface.mae, last.landmarks.stats.mae, last.usable() ? "ok" : "FAILED");
      cases.push_back({{"case", dir.filename().string()}, {"time_s_median", med}, {"time_s_all", times},
                       {"total_s_median", total_med}, {"total_s_all", totals}, {"full_s_median", full_med},
                       {"full_s_all", fulls}, {"cpu_s_median", median(cpus)}, {"cpu_s_all", cpus},
                       {"total_cpu_s_median", median(total_cpus)}, {"total_cpu_s_all", total_cpus},
                       {"full_cpu_s_median", median(full_cpus)}, {"full_cpu_s_all", full_cpus},
                       {"iterations", last.fit.summary.iterations.size()}, {"usable", last.usable()},
                       {"surface_mae_mm", last.surface.mae}, {"landmark_mae_mm", last.landmarks.stats.mae}});
      nlohmann::json phases = nlohmann::json::object();
      for (const auto& [phase, ms] : phase_runs) {
        phases[phase] = median(ms);
        phase_case_medians[phase].push_back(median(ms));
      }
      cases.back()["phases_ms_median"] = phases;
    }
    std::error_code ec;
    std::filesystem::remove_all(scratch, ec);
    double load[1] = {0.0};
    if (getloadavg(load, 1) != 1) load[0] = -1;
    std::fprintf(text, "median over cases of the per-case median time_s: %.4f s, total_s: %.4f s, full_s: %.4f s, cpu_s: "
                "%.4f s, tot_cpu_s: %.4f s, full_cpu_s: %.4f s (%zu cases, %d runs each, %d threads, load average "
                "%.2f)\n",
                median(medians), median(total_medians), median(full_medians), median(cpu_medians),
                median(total_cpu_medians), median(full_cpu_medians), medians.size(), args->repeat, fit::resolve_threads(options.threads), load[0]);
    nlohmann::json median_phases = nlohmann::json::object();
    if (!phase_order.empty()) {
      std::fprintf(text, "phases of the time_s registrations, ms (median over cases of the per-case medians):");
      for (const auto& phase : phase_order) {
        median_phases[phase] = median(phase_case_medians[phase]);
        std::fprintf(text, "%s %s %.1f", phase == phase_order.front() ? "" : ",", phase.c_str(),
                     median(phase_case_medians[phase]));
      }
      std::fprintf(text, "\n");
    }
    if (args->json) {
      std::cout << nlohmann::json{{"cases", cases}, {"median_time_s", median(medians)},
                         {"median_total_s", median(total_medians)}, {"median_full_s", median(full_medians)},
                         {"median_cpu_s", median(cpu_medians)}, {"median_total_cpu_s", median(total_cpu_medians)},
                         {"median_full_cpu_s", median(full_cpu_medians)},
                         {"median_phases_ms", median_phases},
                         {"load_average", load[0]}, {"repeat", args->repeat},
                         {"threads", fit::resolve_threads(options.threads)}}
                .dump(1)
        << "\n";
    }
  });
}

}  // namespace breastfit::cli
