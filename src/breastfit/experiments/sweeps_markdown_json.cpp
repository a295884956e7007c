#include "breastfit/experiments/sweeps_markdown_json.h"

#include <cstdio>
#include <functional>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "breastfit/experiments/markdown_cells_json.h"

namespace breastfit::experiments {
namespace {

using nlohmann::json;

/// Per pose: surface and landmark MAE against the truth and the paper's way, time, flagged runs.
const char* kPoseHeader = " St surf true | St surf scan | St lmk true | St lmk scan | St time s | St flagged |"
                          " Su surf true | Su surf scan | Su lmk true | Su lmk scan | Su time s | Su flagged |";

std::string pose_cells(const json& e) {
  std::ostringstream s;
  for (const char* pose : {"standing", "supine"}) {
    const json& g = json_at(e, {pose});
    s << " " << cell(json_at(g, {"truth", "surface", "mae"})) << " | " << cell(json_at(g, {"paper", "surface", "mae"})) << " | "
      << cell(json_at(g, {"truth", "landmarks", "mae"})) << " | " << cell(json_at(g, {"paper", "landmarks", "mae"})) << " | "
      << cell(json_at(g, {"time_s"}), 3) << " | ";
    auto count = [&](const char* key) { return json_at(g, {key}).is_number() ? json_at(g, {key}).get<int>() : 0; };
    const int flagged = count("n_not_converged") + count("n_not_usable");
    const int errors = json_at(g, {"n_error"}).is_number() ? json_at(g, {"n_error"}).get<int>() : 0;
    if (g.is_null())
      s << "–";
    else
      s << flagged + errors;
    s << " |";
  }
  return s.str();
}

void table(std::ostringstream& os, const std::string& first_headers, const json& summary,
           const std::function<std::string(const json&)>& first_cells) {
  int first_columns = 1;
  for (char c : first_headers) first_columns += c == '|';
  os << "|" << first_headers << kPoseHeader << "\n|";
  for (int k = 0; k < first_columns - 1 + 12; ++k) os << "---|";
  os << "\n";
  for (const auto& e : summary) os << "|" << first_cells(e) << pose_cells(e) << "\n";
}

}  // namespace

std::string sweeps_markdown(const json& j) {
  std::ostringstream os;
  os << "# Sweeps (means over cases)\n\nSt = standing, Su = supine. *surf* = surface MAE, *lmk* = landmark MAE "
        "(all 12 landmarks), mm: *true* against the ground truth, *scan* the paper's way (model → scan, model "
        "landmarks → the landmarks placed on the scan). *time* = mean registration time. *flagged* = fits "
        "reported as not converged or failed (still averaged in when they produced numbers).\n";
  if (j.contains("landmarks")) {
    const json& order = json_at(j, {"landmarks", "order"});
    os << "\n## Fig. 4: number of landmarks used (paper's order)\n\n";
    table(os, " n | landmark added |", json_at(j, {"landmarks", "summary"}), [&](const json& e) {
      const int n = e.value("count", 0);
      std::ostringstream c;
      c << " " << n << " | ";
      if (n > 0 && order.is_array() && n <= static_cast<int>(order.size()))
        c << order[n - 1].get<std::string>();
      else
        c << "–";
      c << " |";
      return c.str();
    });
  }
  if (j.contains("blendshapes")) {
    os << "\n## Figs 5–6: number of blendshapes free (the first n of " << json_at(j, {"blendshapes", "total"}).dump()
       << ")\n\n";
    table(os, " n |", json_at(j, {"blendshapes", "summary"}),
          [](const json& e) {
            std::ostringstream c;
            c << " " << e.value("count", 0) << " |";
            return c.str();
          });
  }
  if (j.contains("lambdas")) {
    os << "\n## Figs 7–8: one λ × factor (defaults:";
    for (const auto& l : json_at(j, {"lambdas", "lambdas"}))
      os << " " << l.value("symbol", "?") << " = " << cell(l["default"], 3);
    os << ")\n\n";
    table(os, " λ | factor | value |", json_at(j, {"lambdas", "summary"}), [](const json& e) {
      std::ostringstream c;
      c << " " << e.value("symbol", std::string("?")) << " | " << cell(e["factor"], 3) << " | " << cell(e["value"], 4)
        << " |";
      return c.str();
    });
  }
  if (j.contains("resolution")) {
    os << "\n## Template resolution\n\n";
    const json& levels = json_at(j, {"resolution", "levels"});
    table(os, " edge mm | vertices | build s |", json_at(j, {"resolution", "summary"}), [&](const json& e) {
      json build = nullptr;
      for (const auto& l : levels)
        if (l["edge_mm"] == e["edge_mm"]) build = l.value("from_cache", false) ? json(nullptr) : l["build_s"];
      std::ostringstream c;
      c << " " << cell(e["edge_mm"], 1) << " | " << e["vertices"].dump() << " | " << cell(build, 1) << " |";
      return c.str();
    });
    os << "\n(build s: – when the template was read from the cache.)\n";
  }
  return os.str();
}

}  // namespace breastfit::experiments
