// breastfit demo: make a synthetic case from the template, register it, compare with the truth.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "breastfit/core/errors.h"
#include "breastfit/io/landmarks_io.h"
#include "breastfit/metrics/truth_errors.h"
#include "breastfit/pipeline/register_outputs.h"
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/synth/case_writer.h"
#include "breastfit/synth/synth_case.h"
#include "command_support.h"
#include "commands.h"
#include "exit_codes.h"

namespace breastfit::cli {

void register_demo(CLI::App& app, int& exit_code) {
  struct Args {
    std::string out = "out/demo", pose = "standing", units = "mm";
    std::uint64_t seed = 7;
    bool force = false, quiet = false;
  };
  auto args = std::make_shared<Args>();
  auto* sub = app.add_subcommand("demo", "The whole pipeline on a synthetic patient: synth a scan with ground "
                                         "truth, register the template, compare with the truth");
  sub->add_option("--out,-o", args->out, "output directory (case/ and fit/ are written inside)");
  sub->add_option("--seed", args->seed, "random seed of the synthetic patient");
  sub->add_option("--pose", args->pose, "standing or supine")->check(CLI::IsMember({"standing", "supine"}));
  sub->add_option("--units", args->units, "units of the synthetic scan files")->check(CLI::IsMember({"mm", "m"}));
  sub->add_flag("--force", args->force, "replace an existing demo output");
  sub->add_flag("--quiet,-q", args->quiet, "no progress lines");
  sub->callback([args, &exit_code] {
    namespace fs = std::filesystem;
    const fs::path out = args->out;
    const fs::path case_dir = out / "case", fit_dir = out / "fit";
    if (!args->force && (fs::exists(case_dir) || fs::exists(fit_dir)))
      throw IoError(out.string(), "already holds a demo (use --force to replace it)");
    const auto model_ptr = std::make_shared<const model::RiggedModel>(load_template(""));
    const model::RiggedModel& model = *model_ptr;

    synth::SynthOptions so;
    so.seed = args->seed;
    so.pose = synth::parse_pose_type(args->pose);
    so.units = args->units;
    const synth::SynthCase c = synth::make_case(model, so);
    synth::write_case(case_dir, c, true);
    std::printf("1. synthetic %s patient (seed %llu): %d-vertex scan with holes, noise and fragments, %zu "
                "landmarks, in %s\n   -> %s\n",
                args->pose.c_str(), static_cast<unsigned long long>(args->seed), c.scan.num_vertices(),
                c.input_landmarks.size(), c.units.c_str(), case_dir.c_str());

    pipeline::RegisterRequest req;
    req.scan = c.scan;
    req.scan_name = (case_dir / "scan.ply").string();
    req.landmarks = io::read_landmarks(case_dir / "landmarks.mrk.json");
    req.model = model_ptr;
    const auto result = pipeline::register_scan(req, progress_printer(args->quiet));
    if (!result.usable()) {
      std::cerr << "breastfit: error: " << req.scan_name << ": " << result.fit.summary.message << "\n";
      pipeline::write_register_failure(fit_dir, result, true, {});  // no stale fit of an earlier demo
      exit_code = kExitNotConverged;
      return;
    }
    pipeline::write_register_outputs(fit_dir, result, model, true, {});
    std::printf("2. ");
    print_register_summary(std::cout, result, fit_dir.string());

    // 3. Against the truth (all in mm).
    const double k = 1.0 / c.scale_mm_to_file_units;
    TriangleMesh truth = c.truth_surface;
    truth.V *= k;
    std::vector<NamedPoint> truth_lm = c.truth_landmarks;
    for (auto& p : truth_lm) p.position *= k;
    const fit::ScanTarget scan(result.scan.mesh_mm, 0);
    const auto te = metrics::truth_errors(result.fit.vertices, truth, scan, result.model_landmarks_mm.points, truth_lm);
    std::printf("3. against the ground truth: surface MAE %.2f mm (max %.1f mm, %d vertices), landmark MAE %.2f mm "
                "(max %.1f mm)\n",
                te.surface.mae, te.surface.max, te.surface.n, te.landmarks.mae, te.landmarks.max);
    for (const auto& curve : result.drawings_mm.curves)
      for (const auto& t : c.truth_curves)
        if (t.name == curve.name) {
          Curve tc = t;
          tc.points *= k;
          std::printf("   %-18s mean distance to the true drawing %.2f mm\n", curve.name.c_str(),
                      metrics::curve_distance(curve, tc));
        }
    std::printf("Open %s/drawings.mrk.json and %s/scan.ply in 3D Slicer to see the drawings on the scan.\n",
                fit_dir.c_str(), case_dir.c_str());
  });
}

}  // namespace breastfit::cli
