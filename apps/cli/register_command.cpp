// breastfit register SCAN [--landmarks FILE] --out DIR: the paper's registration of the template.
#include <algorithm>
#include <exception>
#include <future>
#include <iostream>
#include <type_traits>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/io/landmarks_io.h"
#include "breastfit/model/gltf_io.h"
#include "breastfit/model/template_library.h"
#include "breastfit/pipeline/provenance.h"
#include "breastfit/pipeline/register_outputs.h"
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/pipeline/report_layers.h"
#include "command_support.h"
#include "commands.h"
#include "exit_codes.h"
#include "file_warnings.h"

namespace breastfit::cli {

void register_register(CLI::App& app, int& exit_code) {
  struct Args {
    std::string scan, landmarks, template_path, template_mesh, units = "auto", config, out;
    bool force = false, quiet = false, no_landmarks = false, no_report_html = false;
    FitFlags fit;
  };
  auto args = std::make_shared<Args>();
  auto* sub = app.add_subcommand("register", "Register the rigged template to a scan and write the fitted model, "
                                             "its landmarks and drawings, parameters and a report");
  sub->add_option("scan", args->scan, "scan mesh (.ply .obj .stl .vtk .vtp; a vertex-only file is a point cloud)")->required();
  sub->add_option("--landmarks,-l", args->landmarks, "landmarks on the scan (.mrk.json, .json, .csv or .fcsv)");
  sub->add_flag("--no-landmarks", args->no_landmarks, "ignore landmarks: landmark-free initialisation and fit");
  sub->add_option("--template,-t", args->template_path, "rigged template (.glb/.gltf); default: the shipped torso");
  sub->add_option("--mesh", args->template_mesh,
                  "the template's skinned mesh to use when its file has several (node or mesh name)");
  sub->add_option("--units", args->units, "scan units: auto (from the extent), mm or m")
      ->check(CLI::IsMember({"auto", "mm", "m"}));
  sub->add_option("--config", args->config, "JSON file with fit options (see docs/REGISTRATION.md)");
  sub->add_option("--out,-o", args->out, "output directory (created)")->required();
  sub->add_flag("--force", args->force, "replace existing output files in --out");
  sub->add_flag("--quiet,-q", args->quiet, "no progress lines");
  sub->add_flag("--no-report-html", args->no_report_html,
                "do not write report.html (the human-readable report with images; saves its rendering time)");
  add_fit_flags(*sub, args->fit);
  sub->callback([args, &exit_code] {
    namespace fs = std::filesystem;
    std::vector<fs::path> inputs{args->scan};
    if (!args->landmarks.empty()) inputs.push_back(args->landmarks);
    if (!args->config.empty()) inputs.push_back(args->config);
    if (!args->template_path.empty()) inputs.push_back(args->template_path);
    pipeline::check_output_dir(args->out, args->force, inputs);

    // The template is loaded and the inputs hashed for the provenance on another thread while
    // this one reads the scan and builds its index; a template error still comes before any
    // error of the options or the scan's preparation, as when it was loaded first.
    struct Loaded {
      std::shared_ptr<const model::RiggedModel> model;
      pipeline::Provenance provenance;
    };
    std::shared_future<Loaded> loaded = std::async(std::launch::async, [args] {
      Loaded l;
      l.model = std::make_shared<const model::RiggedModel>(load_template(args->template_path, args->template_mesh));
      l.provenance = pipeline::start_provenance(
          pipeline::shell_command_line(command_line()),
          {{"scan", args->scan},
           {"landmarks", args->no_landmarks ? fs::path() : fs::path(args->landmarks)},
           {"template", args->template_path.empty() ? model::default_template_path() : fs::path(args->template_path)},
           {"config", args->config}});
      return l;
    }).share();

    pipeline::RegisterRequest req;
    req.scan = io::read_mesh(args->scan);
    req.scan_name = args->scan;
    req.units = parse_units_flag(args->units);
    req.landmarks_name = args->landmarks;
    if (!args->landmarks.empty() && !args->no_landmarks) req.landmarks = read_landmarks_warning(args->landmarks);
    pipeline::RegisterOutputOptions output_options;
    output_options.report_html = !args->no_report_html;
    // The report's overlay figures' scan layers are drawn on a thread of their own from when the
    // scan is prepared (before its index is built, the template perhaps still loading) while the
    // fit runs; nothing when the fit will be landmark-free.
    auto start_layers = [&](const pipeline::PreparedScan& scan) {
      if (output_options.report_html)
        output_options.layers = pipeline::start_report_layers(
            scan, req.landmarks, req.options, [loaded] { return loaded.get().model; }, output_options.figures);
    };
    std::exception_ptr later_error;
    pipeline::PreparedTarget target;
    try {
      req.options = load_fit_options(args->config, args->fit);
      if (args->no_landmarks) req.options.use_landmarks = false;
      // The report's layers drawn beside the fit keep a core busy: an automatic thread count leaves
      // it to them.
      if (output_options.report_html) req.options.threads = pipeline::fit_threads_beside_layers(req.landmarks, req.options);
      // The scan as read is needed no more once prepared: its arrays are taken over, not copied.
      target = pipeline::prepare_target(std::move(req.scan), req.scan_name, req.units, req.options, start_layers);
      target.single_use = true;  // one fit: the result takes the prepared scan instead of a copy
    } catch (...) {
      later_error = std::current_exception();
    }
    Loaded l = loaded.get();
    if (later_error) std::rethrow_exception(later_error);
    req.model = l.model;
    req.provenance = std::move(l.provenance);
    const model::RiggedModel& model = *req.model;

    auto result = pipeline::register_prepared(req, target, progress_printer(args->quiet));
    result.time_s += target.timings.back().seconds;  // as register_scan: the index build included
    if (!result.usable()) {
      std::cerr << "breastfit: error: " << args->scan << ": " << result.fit.summary.message << "\n";
      // Keep the evidence, but no fitted outputs (not even the previous run's) that could be
      // mistaken for a result.
      pipeline::write_register_failure(args->out, result, args->force, inputs);
      exit_code = kExitNotConverged;
      return;
    }
    // The scan's index and the scan as read are not needed any more: freed before the outputs
    // are written, their memory is reused by the report's figures instead of fresh pages, which
    // the kernel zeroes on first touch (docs/PERFORMANCE.md, "Page faults").
    auto release = [](auto& x) { std::decay_t<decltype(x)> gone = std::move(x); };
    release(target);
    release(req.scan);
    pipeline::write_register_outputs(args->out, result, model, args->force, inputs, output_options);
    if (result.fit.summary.initialization == "landmark-free")  // one line, quiet or not
      std::cerr << "breastfit: " << (args->landmarks.empty() || args->no_landmarks ? "no landmarks given: " : "")
                << result.fit.summary.initialization_detail << "\n";
    for (const auto& w : result.warnings) std::cerr << "breastfit: warning: " << w << "\n";
    if (!args->quiet) print_register_summary(std::cout, result, args->out, output_options.report_html);
    if (!result.plausibility.plausible) exit_code = kExitImplausible;
  });
}

}  // namespace breastfit::cli
