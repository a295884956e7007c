#include "breastfit/experiments/run_summary_json.h"

#include <cmath>
#include <functional>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

namespace breastfit::experiments {
namespace {

/// Mean of f over the runs where it is finite; null when none.
nlohmann::json mean(const std::vector<const RunRecord*>& runs, const std::function<double(const RunRecord&)>& f) {
  double sum = 0;
  int n = 0;
  for (const RunRecord* r : runs) {
    const double v = f(*r);
    if (std::isfinite(v)) {
      sum += v;
      ++n;
    }
  }
  return n > 0 ? nlohmann::json(sum / n) : nlohmann::json(nullptr);
}

using StatsOf = std::function<const metrics::DistanceStats&(const RunRecord&)>;

nlohmann::json stats_means(const std::vector<const RunRecord*>& runs, const StatsOf& s, bool with_min) {
  nlohmann::json j = {{"mae", mean(runs, [&](const RunRecord& r) { return s(r).mae; })},
                      {"sd", mean(runs, [&](const RunRecord& r) { return s(r).sd; })},
                      {"max", mean(runs, [&](const RunRecord& r) { return s(r).max; })}};
  if (with_min) j["min"] = mean(runs, [&](const RunRecord& r) { return s(r).min; });
  return j;
}

nlohmann::json group(const std::vector<const RunRecord*>& all) {
  std::vector<const RunRecord*> with_numbers, with_truth;
  int not_converged = 0, not_usable = 0, errors = 0;
  for (const RunRecord* r : all) {
    if (r->status == "not_converged") ++not_converged;
    if (r->status == "not_usable") ++not_usable;
    if (!r->has_numbers()) {
      ++errors;
      continue;
    }
    with_numbers.push_back(r);
    if (r->has_truth) with_truth.push_back(r);
  }
  nlohmann::json g = {
      {"n", all.size()},
      {"n_not_converged", not_converged},
      {"n_not_usable", not_usable},
      {"n_error", errors},
      {"time_s", mean(with_numbers, [](const RunRecord& r) { return r.time_s; })},
      {"iterations", mean(with_numbers, [](const RunRecord& r) { return static_cast<double>(r.iterations); })},
      {"paper",
       {{"surface", stats_means(with_numbers, [](const RunRecord& r) -> const auto& { return r.paper_surface; }, false)},
        {"landmarks",
         stats_means(with_numbers, [](const RunRecord& r) -> const auto& { return r.paper_landmarks; }, true)}}}};
  if (!with_truth.empty()) {
    std::map<std::string, bool> names;
    for (const RunRecord* r : with_truth)
      for (const auto& [name, v] : r->drawings_mm) names[name] = true;
    nlohmann::json d = nlohmann::json::object();
    for (const auto& [name, _] : names)
      d[name] = mean(with_truth, [&name](const RunRecord& r) {
        for (const auto& [n, v] : r.drawings_mm)
          if (n == name) return v;
        return std::nan("");
      });
    g["truth"] = {
        {"n", with_truth.size()},
        {"surface", stats_means(with_truth, [](const RunRecord& r) -> const auto& { return r.truth_surface; }, false)},
        {"landmarks", stats_means(with_truth, [](const RunRecord& r) -> const auto& { return r.truth_landmarks; }, true)},
        {"drawings_mm", d}};
  }
  return g;
}

}  // namespace

nlohmann::json summarize(const std::vector<const RunRecord*>& runs) {
  nlohmann::json out = nlohmann::json::object();
  for (const char* pose : {"standing", "supine"}) {
    std::vector<const RunRecord*> sel;
    for (const RunRecord* r : runs)
      if (r->pose == pose) sel.push_back(r);
    if (!sel.empty()) out[pose] = group(sel);
  }
  out["all"] = group(runs);
  return out;
}

}  // namespace breastfit::experiments
