#include "breastfit/experiments/experiment_suite_json.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/core/timer.h"
#include "breastfit/experiments/case_runner.h"
#include "breastfit/experiments/case_set.h"
#include "breastfit/experiments/experiment_options_json.h"
#include "breastfit/experiments/resolution_templates.h"
#include "breastfit/experiments/run_record_json.h"
#include "breastfit/experiments/run_summary_json.h"
#include "breastfit/mesh/landmark_names.h"
#include "breastfit/pipeline/register_outputs.h"
#include "breastfit/template/default_template.h"

namespace breastfit::experiments {
namespace {

namespace fs = std::filesystem;

/// One registration of an experiment with the setting it was run with (e.g. {"count": 3}).
struct Tagged {
  nlohmann::json setting;
  RunRecord record;
};

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

nlohmann::json runs_json(const std::vector<Tagged>& runs) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& t : runs) {
    nlohmann::json j = t.setting;
    j.update(to_json(t.record));
    a.push_back(std::move(j));
  }
  return a;
}

/// Summary per distinct setting, in the order settings first appear.
nlohmann::json summaries(const std::vector<Tagged>& runs) {
  std::vector<nlohmann::json> settings;
  for (const auto& t : runs)
    if (std::find(settings.begin(), settings.end(), t.setting) == settings.end()) settings.push_back(t.setting);
  nlohmann::json out = nlohmann::json::array();
  for (const auto& s : settings) {
    std::vector<const RunRecord*> sel;
    for (const auto& t : runs)
      if (t.setting == s) sel.push_back(&t.record);
    nlohmann::json j = s;
    j.update(summarize(sel));
    out.push_back(std::move(j));
  }
  return out;
}

std::vector<int> sorted_unique(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

std::vector<double> lambda_factors_with_one(const std::vector<double>& f) {
  std::vector<double> v = f;
  v.push_back(1.0);
  std::sort(v.begin(), v.end());
  std::vector<double> out;
  for (double x : v)
    if (out.empty() || std::abs(std::log(x / out.back())) > 1e-9) out.push_back(x);
  return out;
}

std::string brief(const RunRecord& r) {
  if (!r.has_numbers()) return "error: " + r.message;
  std::string s = fmt("%.2f s, surface ", r.time_s) + fmt("%.2f", r.paper_surface.mae);
  if (r.has_truth) s += fmt(" (truth %.2f)", r.truth_surface.mae);
  s += fmt(" mm, landmarks %.2f", r.paper_landmarks.mae);
  if (r.has_truth) s += fmt(" (truth %.2f)", r.truth_landmarks.mae);
  s += " mm";
  if (r.status != "ok") s += " [" + r.status + "]";
  return s;
}

}  // namespace

nlohmann::json run_experiments(const std::vector<fs::path>& case_dirs, const model::RiggedModel& model,
                               const ExperimentOptions& o, const ProgressFn& progress) {
  o.validate();
  const auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  Timer wall;
  const int num_bs = model.num_blendshapes();

  // Grids, resolved against the template.
  const std::vector<int> lm_counts = sorted_unique(o.landmark_counts);
  std::vector<int> bs_counts;
  for (int n : o.blendshape_counts) bs_counts.push_back(n < 0 || n > num_bs ? num_bs : n);
  bs_counts = sorted_unique(bs_counts);
  const std::vector<double> factors = lambda_factors_with_one(o.lambda_factors);

  // Resolution templates, built (or read from the cache) before any case.
  const std::uint64_t base_fp = template_fingerprint(model);
  std::vector<ResolutionTemplate> levels;
  std::vector<bool> level_is_default;
  nlohmann::json levels_json = nlohmann::json::array();
  if (o.runs("resolution")) {
    std::vector<double> edges = o.resolution_edges_mm;
    std::sort(edges.begin(), edges.end(), std::greater<>());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (double e : edges) {
      say("resolution: template with " + fmt("%.1f", e) + " mm edges ...");
      levels.push_back(resolution_template(e, o.template_cache_dir, base_fp));
      const auto& L = levels.back();
      const bool same = template_fingerprint(L.model) == base_fp;
      level_is_default.push_back(same);
      say("resolution: " + std::to_string(L.model.num_vertices()) + " vertices" +
          (L.from_cache ? " (cached)" : fmt(", built in %.1f s", L.build_s)) +
          (same ? ", identical to the template in use" : ""));
      levels_json.push_back({{"edge_mm", L.edge_mm},
                             {"grid_step_mm", L.grid_step_mm},
                             {"vertices", L.model.num_vertices()},
                             {"faces", L.model.rest.num_faces()},
                             {"blendshapes", L.model.num_blendshapes()},
                             {"build_s", L.build_s},
                             {"from_cache", L.from_cache},
                             {"file", L.file.string()},
                             {"same_as_template_in_use", same}});
    }
  }

  std::vector<Tagged> table1, lm_runs, bs_runs, lambda_runs, res_runs;
  nlohmann::json cases = nlohmann::json::array();
  int index = 0;
  for (const fs::path& dir : case_dirs) {
    ++index;
    char counter[48];
    std::snprintf(counter, sizeof counter, "[%d/%zu] ", index, case_dirs.size());
    const std::string tag = counter + dir.filename().string();
    Timer case_timer;
    std::optional<EvalCase> c;
    try {
      c = load_case(dir);
    } catch (const std::exception& e) {
      say(tag + ": cannot be loaded: " + e.what());
      cases.push_back({{"id", dir.filename().string()}, {"error", e.what()}});
      continue;
    }
    std::optional<CaseRunner> runner;
    try {
      runner.emplace(*c);
    } catch (const std::exception& e) {
      say(tag + ": cannot be registered: " + e.what());
      cases.push_back({{"id", c->id}, {"pose", c->pose}, {"error", e.what()}});
      continue;
    }
    int runs = 0;
    const auto run = [&](const model::RiggedModel& m, const fit::FitOptions& fo) {
      ++runs;
      return runner->run(m, fo);
    };

    // Table 1 (and the default run the other experiments reuse).
    ++runs;
    const RunRecord def = runner->run(model, o.fit, [&](const pipeline::RegisterResult& r) {
      if (!o.contract_dir.empty() && o.runs("table1"))
        pipeline::write_register_outputs(o.contract_dir / c->id, r, model, /*force=*/true, {});
    });
    say(tag + " (" + c->pose + "): default: " + brief(def));
    if (o.runs("table1")) table1.push_back({nlohmann::json::object(), def});

    if (o.runs("landmarks") && c->landmarks) {
      for (int n : lm_counts) {
        fit::FitOptions fo = o.fit;
        fo.use_landmarks = true;
        fo.max_landmarks = n;
        const bool is_default = n >= static_cast<int>(c->landmarks->points.size()) && o.fit.max_landmarks < 0 &&
                                o.fit.use_landmarks;
        lm_runs.push_back({{{"count", n}}, is_default ? def : run(model, fo)});
      }
    }
    if (o.runs("blendshapes")) {
      for (int n : bs_counts) {
        fit::FitOptions fo = o.fit;
        fo.max_blendshapes = n;
        const bool is_default = n >= num_bs && o.fit.max_blendshapes < 0;
        bs_runs.push_back({{{"count", n}}, is_default ? def : run(model, fo)});
      }
    }
    if (o.runs("lambdas")) {
      for (const auto& spec : sensitivity_lambdas()) {
        for (double f : factors) {
          fit::FitOptions fo = o.fit;
          scale_lambda(fo.weights, spec.field, f);
          const double v = lambda_value(fo.weights, spec.field);
          const nlohmann::json setting = {{"lambda", spec.field}, {"symbol", spec.symbol}, {"factor", f}, {"value", v}};
          lambda_runs.push_back({setting, f == 1.0 ? def : run(model, fo)});
        }
      }
    }
    if (o.runs("resolution")) {
      for (size_t k = 0; k < levels.size(); ++k) {
        const nlohmann::json setting = {{"edge_mm", levels[k].edge_mm}, {"vertices", levels[k].model.num_vertices()}};
        res_runs.push_back({setting, level_is_default[k] ? def : run(levels[k].model, o.fit)});
      }
    }
    const double secs = case_timer.seconds();
    say(tag + ": " + std::to_string(runs) + " registrations in " + fmt("%.1f s", secs));
    cases.push_back({{"id", c->id},
                     {"pose", c->pose},
                     {"units", std::string(mesh::units_name(c->units))},
                     {"scan_vertices", c->scan.num_vertices()},
                     {"scan_faces", c->scan.num_faces()},
                     {"landmarks", c->landmarks ? c->landmarks->points.size() : 0},
                     {"has_truth", c->truth.has_value()},
                     {"registrations", runs},
                     {"seconds", secs}});
  }

  nlohmann::json names = nlohmann::json::array();
  for (auto n : kLandmarkNames) names.push_back(std::string(n));
  nlohmann::json bs_names = nlohmann::json::array();
  for (const auto& b : model.blendshapes) bs_names.push_back(b.name);

  nlohmann::json out;
  out["generator"] = "breastfit experiments";
  nlohmann::json config = to_json(o);
  config["landmark_order"] = names;
  config["template"] = {{"name", model.name},
                        {"vertices", model.num_vertices()},
                        {"faces", model.rest.num_faces()},
                        {"blendshapes", num_bs},
                        {"bones", model.num_bones()},
                        {"fingerprint", std::to_string(base_fp)}};
  out["config"] = config;
  out["cases"] = cases;
  if (o.runs("table1")) out["table1"] = {{"runs", runs_json(table1)}, {"summary", summarize([&] {
                                           std::vector<const RunRecord*> v;
                                           for (const auto& t : table1) v.push_back(&t.record);
                                           return v;
                                         }())}};
  if (o.runs("landmarks"))
    out["landmarks"] = {{"order", names}, {"counts", lm_counts}, {"runs", runs_json(lm_runs)},
                        {"summary", summaries(lm_runs)}};
  if (o.runs("blendshapes"))
    out["blendshapes"] = {{"total", num_bs}, {"names", bs_names}, {"counts", bs_counts},
                          {"runs", runs_json(bs_runs)}, {"summary", summaries(bs_runs)}};
  if (o.runs("lambdas")) {
    nlohmann::json lambdas = nlohmann::json::array();
    for (const auto& spec : sensitivity_lambdas()) {
      lambdas.push_back({{"field", spec.field}, {"symbol", spec.symbol}, {"default", lambda_value(o.fit.weights, spec.field)}});
    }
    out["lambdas"] = {{"lambdas", lambdas}, {"factors", factors}, {"runs", runs_json(lambda_runs)},
                      {"summary", summaries(lambda_runs)}};
  }
  if (o.runs("resolution"))
    out["resolution"] = {{"levels", levels_json}, {"runs", runs_json(res_runs)}, {"summary", summaries(res_runs)}};
  out["wall_time_s"] = wall.seconds();
  return out;
}

}  // namespace breastfit::experiments
