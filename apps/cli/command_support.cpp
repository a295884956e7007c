#include "command_support.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/fit/energy_terms.h"
#include "breastfit/fit/fit_options_json.h"
#include "breastfit/model/gltf_io.h"
#include "breastfit/model/template_library.h"
#include "breastfit/pipeline/register_scan.h"

namespace breastfit::cli {

void add_fit_flags(CLI::App& sub, FitFlags& f) {
  auto* g = sub.add_option_group("fit weights", "energy weights (E = Σ term/λ; smaller λ = stronger term)");
  for (const auto& t : fit::energy_terms()) {
    std::string flag = "--lambda-" + std::string(t.name);
    std::replace(flag.begin(), flag.end(), '_', '-');
    char help[256];
    std::snprintf(help, sizeof help, "%s, %s (%s; default %g%s)", std::string(t.symbol).c_str(),
                  std::string(t.help).c_str(), std::string(t.units).c_str(), t.default_lambda,
                  t.can_disable ? "; <= 0 disables" : "");
    g->add_option(flag, f.lambdas[std::string(t.name)], help);
  }
  g->add_option("--max-blendshapes", f.max_blendshapes, "use only the first N blendshapes (default: all)");
  g->add_option("--max-landmarks", f.max_landmarks, "use only the first N landmarks (paper order; default: all given)");
  g->add_flag("--no-surface-detail", f.no_surface_detail,
              "the paper's model only: no smooth normal offsets fitted after the parameters");
  sub.add_option("--threads", f.threads,
                 "threads for the registration (default 0: the cores not busy with other work, "
                 "docs/PERFORMANCE.md); the results do not depend on it")
      ->check(CLI::Range(0, 1024));
}

fit::FitOptions load_fit_options(const std::string& config_path, const FitFlags& f) {
  fit::FitOptions o;
  if (!config_path.empty()) {
    std::ifstream in(config_path);
    if (!in) throw IoError(config_path, "cannot open the config file");
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      throw IoError(config_path, std::string("not valid JSON: ") + e.what());
    }
    try {
      fit::update_from_json(o, j);
    } catch (const InvalidInput& e) {
      throw IoError(config_path, e.what());
    }
  }
  for (const auto& [term, value] : f.lambdas)
    if (value) o.weights.set_lambda(term, *value);
  if (f.max_blendshapes) o.max_blendshapes = *f.max_blendshapes;
  if (f.max_landmarks) o.max_landmarks = *f.max_landmarks;
  if (f.no_surface_detail) o.detail.enabled = false;
  if (f.threads) o.threads = *f.threads;
  o.validate();
  return o;
}

std::optional<mesh::Units> parse_units_flag(const std::string& text) {
  if (text == "auto") return std::nullopt;
  const auto u = mesh::parse_units(text);
  if (!u) throw InvalidInput("--units '" + text + "': expected auto, mm or m");
  return u;
}

void check_output_file(const std::string& path, const std::vector<std::string>& inputs, bool force,
                       const std::string& force_flag) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) return;
  for (const std::string& in : inputs)
    if (fs::equivalent(path, in, ec)) throw IoError(path, "is an input: choose another output");
  if (!force) throw IoError(path, "already exists (use " + force_flag + " to replace it)");
}

namespace {
std::vector<std::string>& command_line_storage() {
  static std::vector<std::string> args;
  return args;
}
}  // namespace

void set_command_line(int argc, const char* const* argv) {
  command_line_storage().assign(argv, argv + argc);
}

const std::vector<std::string>& command_line() { return command_line_storage(); }

model::RiggedModel load_template(const std::string& path, const std::string& mesh) {
  const std::filesystem::path p = path.empty() ? model::default_template_path() : std::filesystem::path(path);
  return model::load_gltf(p, mesh);
}

fit::IterationCallback progress_printer(bool quiet) {
  if (quiet) return {};
  return [](const fit::IterationRecord& r) {
    std::fprintf(stderr, "  %-6s %3d  E %.5g -> %.5g  d<%.1f mm  kept %d  %s\n", r.stage.c_str(), r.iteration,
                 r.energy_before, r.energy_after, r.max_distance_mm, r.kept, r.accepted ? "" : "(rejected step)");
    return fit::CallbackResult::Continue;
  };
}

void print_register_summary(std::ostream& os, const pipeline::RegisterResult& r, const std::string& out_dir,
                            bool report_html) {
  char buf[512];
  const auto& s = r.fit.summary;
  std::snprintf(buf, sizeof buf,
                "registered in %.3f s (%zu iterations, %s); units %s\n"
                "  surface error (fitted vertices -> scan): MAE %.2f mm, SD %.2f mm, max %.1f mm (%d vertices)\n",
                r.time_s, s.iterations.size(), s.message.c_str(), std::string(mesh::units_name(r.scan.units)).c_str(),
                r.surface.mae, r.surface.sd, r.surface.max, r.surface.n);
  os << buf;
  if (r.scan.units_detected)
    os << "  units: " << mesh::units_name(r.scan.units) << ", from the scan's extent ("
       << r.scan.extent << " " << mesh::units_name(r.scan.units) << "; a torso is 250-700 mm)\n";
  if (!s.initialization_detail.empty()) os << "  initialisation: " << s.initialization_detail << "\n";
  if (s.detail.applied) {
    std::snprintf(buf, sizeof buf,
                  "  surface detail: offsets along the normals mean %.2f mm, max %.1f mm (template alone: MAE %.2f mm)\n",
                  s.detail.mean_abs_mm, s.detail.max_abs_mm, r.surface_model_only.mae);
    os << buf;
  }
  if (r.landmarks.stats.n > 0) {
    std::snprintf(buf, sizeof buf, "  landmark error (%d landmarks): MAE %.2f mm, SD %.2f mm, max %.1f mm, min %.1f mm\n",
                  r.landmarks.stats.n, r.landmarks.stats.mae, r.landmarks.stats.sd, r.landmarks.stats.max,
                  r.landmarks.stats.min);
    os << buf;
  }
  for (const auto& c : r.drawings_on_scan) {
    std::snprintf(buf, sizeof buf, "  drawing %-18s %6.1f mm long, %3.0f%% on the scan, %.2f mm from the model\n",
                  c.name.c_str(), c.length_mm, 100 * c.supported_fraction, c.mean_model_to_scan_mm);
    os << buf;
  }
  os << "  outputs: " << out_dir
     << "/{fitted.ply, landmarks.mrk.json, drawings.mrk.json, drawings.ply, drawings.obj, scan_painted.ply, "
        "params.json, report.json"
     << (report_html ? ", report.html" : "") << "}\n";
}

}  // namespace breastfit::cli
