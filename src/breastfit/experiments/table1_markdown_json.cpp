#include "breastfit/experiments/table1_markdown_json.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "breastfit/experiments/markdown_cells_json.h"

namespace breastfit::experiments {
namespace {

using nlohmann::json;

std::string num(double v, int digits = 2) { return cell(json(v), digits); }

/// Mean of the numbers among `values` (null when none).
json mean(const std::vector<json>& values) {
  double s = 0;
  int n = 0;
  for (const auto& v : values)
    if (v.is_number()) {
      s += v.get<double>();
      ++n;
    }
  return n ? json(s / n) : json(nullptr);
}

/// Appends " | value" for each column path of `record`, collecting the values per column.
void append_cells(std::ostringstream& os, const json& record, const std::vector<std::vector<const char*>>& cols,
                  std::vector<std::vector<json>>& sums) {
  for (size_t k = 0; k < cols.size(); ++k) {
    const json& v = json_at(record, cols[k]);
    sums[k].push_back(v);
    os << " | " << cell(v);
  }
}

/// The bold mean row of the collected columns (its status cell empty).
void append_mean_row(std::ostringstream& os, const std::vector<std::vector<json>>& sums) {
  os << "| **mean**";
  for (const auto& col : sums) os << " | **" << cell(mean(col)) << "**";
  os << " | |\n";
}

const char* kPaperHeader =
    "| Case | Time s | Surf MAE | SD | Max | Lmk MAE | SD | Max | Min | True surf MAE | SD | Max | True lmk MAE | SD | "
    "Max | Min | Contour R | Contour L | Sternum | IMF R | IMF L | Status |\n"
    "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";

std::vector<std::vector<const char*>> our_columns() {
  return {{"time_s"},
          {"paper", "surface", "mae"},
          {"paper", "surface", "sd"},
          {"paper", "surface", "max"},
          {"paper", "landmarks", "mae"},
          {"paper", "landmarks", "sd"},
          {"paper", "landmarks", "max"},
          {"paper", "landmarks", "min"},
          {"truth", "surface", "mae"},
          {"truth", "surface", "sd"},
          {"truth", "surface", "max"},
          {"truth", "landmarks", "mae"},
          {"truth", "landmarks", "sd"},
          {"truth", "landmarks", "max"},
          {"truth", "landmarks", "min"},
          {"truth", "drawings_mm", "breast_contour_R"},
          {"truth", "drawings_mm", "breast_contour_L"},
          {"truth", "drawings_mm", "sternum"},
          {"truth", "drawings_mm", "imf_R"},
          {"truth", "drawings_mm", "imf_L"}};
}

void our_table(std::ostringstream& os, const json& runs, const std::string& pose) {
  const auto cols = our_columns();
  std::vector<std::vector<json>> sums(cols.size());
  os << kPaperHeader;
  for (const auto& r : runs) {
    if (r.value("pose", "") != pose) continue;
    os << "| " << r.value("case", "?");
    append_cells(os, r, cols, sums);
    os << " | " << r.value("status", "?") << " |\n";
  }
  append_mean_row(os, sums);
  const PaperTable1Mean p = paper_table1_mean(pose);
  os << "| *paper, mean* | " << num(p.time_s) << " | " << num(p.surface_mae) << " | " << num(p.surface_sd) << " | "
     << num(p.surface_max, 1) << " | " << num(p.landmark_mae) << " | " << num(p.landmark_sd) << " | "
     << num(p.landmark_max, 1) << " | " << num(p.landmark_min)
     << " | – | – | – | – | – | – | – | – | – | – | – | – | |\n";
}

void referee_table(std::ostringstream& os, const json& referee_cases, const std::map<std::string, std::string>& pose_of,
                   const std::string& pose) {
  const std::vector<std::vector<const char*>> cols = {
      {"tool_reported_time_s"},        {"surface_scan", "mae"},        {"surface_scan", "sd"},
      {"surface_scan", "max"},         {"surface_true", "mae"},        {"surface_true", "sd"},
      {"surface_true", "max"},         {"surface_true_reverse", "mae"}, {"landmarks", "mae"},
      {"landmarks", "sd"},             {"landmarks", "max"},           {"landmarks", "min"},
      {"curves", "breast_contour_R", "mean_sym"}, {"curves", "breast_contour_L", "mean_sym"},
      {"curves", "sternum", "mean_sym"}, {"curves", "imf_R", "mean_sym"}, {"curves", "imf_L", "mean_sym"}};
  std::vector<std::vector<json>> sums(cols.size());
  os << "| Case | Time s | Scan MAE | SD | Max | True MAE | SD | Max | Rev MAE | Lmk MAE | SD | Max | Min | Contour R | "
        "Contour L | Sternum | IMF R | IMF L | Status |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : referee_cases) {
    const std::string id = r.value("case", "?");
    const auto it = pose_of.find(id);
    if (it == pose_of.end() || it->second != pose) continue;
    os << "| " << id;
    append_cells(os, r, cols, sums);
    os << " | " << r.value("status", "?") << " |\n";
  }
  append_mean_row(os, sums);
}

/// The paper's Table 1 with the truth columns of the referee: model → scan and model landmarks →
/// placed landmarks from breastfit (the referee's "Scan MAE" is the same measure), against the
/// truth from the referee.
void combined_table(std::ostringstream& os, const json& runs, const json& referee_cases, const std::string& pose) {
  // (false, path) = breastfit's run record, (true, path) = the referee's case.
  const std::vector<std::pair<bool, std::vector<const char*>>> cols = {
      {false, {"time_s"}},
      {false, {"paper", "surface", "mae"}},
      {false, {"paper", "surface", "sd"}},
      {false, {"paper", "surface", "max"}},
      {false, {"paper", "landmarks", "mae"}},
      {false, {"paper", "landmarks", "sd"}},
      {false, {"paper", "landmarks", "max"}},
      {false, {"paper", "landmarks", "min"}},
      {true, {"surface_true", "mae"}},
      {true, {"surface_true", "sd"}},
      {true, {"surface_true", "max"}},
      {true, {"landmarks", "mae"}},
      {true, {"landmarks", "sd"}},
      {true, {"landmarks", "max"}},
      {true, {"landmarks", "min"}},
      {true, {"curves", "breast_contour_R", "mean_sym"}},
      {true, {"curves", "breast_contour_L", "mean_sym"}},
      {true, {"curves", "sternum", "mean_sym"}}};
  std::vector<std::vector<json>> sums(cols.size());
  os << "| Case | Time s | Surf MAE | SD | Max | Lmk MAE | SD | Max | Min | True surf MAE | SD | Max | True lmk MAE | SD | "
        "Max | Min | Contour R | Contour L | Sternum |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  static const json none = json::object();
  for (const auto& r : runs) {
    if (r.value("pose", "") != pose) continue;
    const json* ref = &none;
    for (const auto& q : referee_cases)
      if (q.value("case", "") == r.value("case", "")) ref = &q;
    os << "| " << r.value("case", "?");
    for (size_t k = 0; k < cols.size(); ++k) {
      const json& v = json_at(cols[k].first ? *ref : r, cols[k].second);
      sums[k].push_back(v);
      os << " | " << cell(v);
    }
    os << " |\n";
  }
  os << "| **mean**";
  for (auto& s : sums) os << " | **" << cell(mean(s)) << "**";
  os << " |\n";
  const PaperTable1Mean p = paper_table1_mean(pose);
  os << "| *paper, mean* | " << num(p.time_s) << " | " << num(p.surface_mae) << " | " << num(p.surface_sd) << " | "
     << num(p.surface_max, 1) << " | " << num(p.landmark_mae) << " | " << num(p.landmark_sd) << " | "
     << num(p.landmark_max, 1) << " | " << num(p.landmark_min) << " | – | – | – | – | – | – | – | – | – | – |\n";
}

/// How far breastfit's own truth metrics are from the referee's, case by case.
void agreement(std::ostringstream& os, const json& runs, const json& referee_cases) {
  const std::vector<std::pair<const char*, std::pair<std::vector<const char*>, std::vector<const char*>>>> rows = {
      {"true surface MAE", {{"truth", "surface", "mae"}, {"surface_true", "mae"}}},
      {"landmark MAE", {{"truth", "landmarks", "mae"}, {"landmarks", "mae"}}},
      {"contour R", {{"truth", "drawings_mm", "breast_contour_R"}, {"curves", "breast_contour_R", "mean_sym"}}},
      {"contour L", {{"truth", "drawings_mm", "breast_contour_L"}, {"curves", "breast_contour_L", "mean_sym"}}},
      {"sternum", {{"truth", "drawings_mm", "sternum"}, {"curves", "sternum", "mean_sym"}}}};
  os << "\n## breastfit's truth metrics against the referee's (same fits)\n\n| metric | cases | mean ours | mean "
        "referee | mean \\|ours − referee\\| | max \\|ours − referee\\| |\n|---|---|---|---|---|---|\n";
  for (const auto& [name, paths] : rows) {
    double sum_ours = 0, sum_ref = 0, sum_abs = 0, max_abs = 0;
    int n = 0;
    for (const auto& r : runs)
      for (const auto& q : referee_cases)
        if (q.value("case", "") == r.value("case", "")) {
          const json& a = json_at(r, paths.first);
          const json& b = json_at(q, paths.second);
          if (!a.is_number() || !b.is_number()) continue;
          const double d = std::abs(a.get<double>() - b.get<double>());
          sum_ours += a.get<double>();
          sum_ref += b.get<double>();
          sum_abs += d;
          max_abs = std::max(max_abs, d);
          ++n;
        }
    if (n == 0) continue;
    os << "| " << name << " | " << n << " | " << num(sum_ours / n) << " | " << num(sum_ref / n) << " | "
       << num(sum_abs / n) << " | " << num(max_abs) << " |\n";
  }
}

}  // namespace

PaperTable1Mean paper_table1_mean(const std::string& pose) {
  if (pose == "supine") return {2.20, 2.28, 3.06, 23.5, 7.61, 3.95, 14.7, 1.75};
  return {1.85, 2.41, 3.19, 31.4, 8.46, 4.85, 18.1, 1.98};
}

std::string table1_markdown(const json& j) {
  std::ostringstream os;
  const json& runs = json_at(j, {"table1", "runs"});
  std::map<std::string, std::string> pose_of;
  if (runs.is_array())
    for (const auto& r : runs) pose_of[r.value("case", "")] = r.value("pose", "unknown");
  const char* titles[2][2] = {{"standing", "Standing (the paper's preoperative configuration)"},
                              {"supine", "Supine (the paper's intra-operative configuration)"}};
  os << "# Table 1\n\nDistances in mm, times in s. *Surf* = fitted template vertices → scan (scan-border matches "
        "excluded) and *Lmk* = model landmarks → the 12 landmarks placed on the scan: the paper's way. *True* = "
        "against the ground truth (fitted vertices → true surface over its observed part; model landmarks → true "
        "landmarks); drawings = mean symmetric distance of each transferred drawing to the true one "
        "(breastfit's own metrics). Time = scan and landmarks in memory → fitted parameters.\n";
  const json& ref = json_at(j, {"referee", "cases"});
  if (ref.is_array() && runs.is_array()) {
    os << "\n## As in the paper, with the truth scored by the external referee\n\n*Surf*, *Lmk* (the paper's way) "
          "from breastfit; *True*, contours and sternum from the referee on the same fits.\n";
    for (const auto& t : titles) {
      os << "\n### " << t[1] << "\n\n";
      combined_table(os, runs, ref, t[0]);
    }
    os << "\n# breastfit's own metrics\n";
  }
  for (const auto& t : titles) {
    os << "\n## " << t[1] << "\n\n";
    if (runs.is_array()) our_table(os, runs, t[0]);
  }
  if (ref.is_array()) {
    const json& cmd = json_at(j, {"referee", "command"});
    os << "\n# Table 1 scored by the external referee\n\n`" << (cmd.is_string() ? cmd.get<std::string>() : "?")
       << "`\n\nScan = the paper's surface error; True = against the truth over the observed region; Rev = "
          "observed truth → fitted surface; Lmk = model landmarks → true landmarks; curves = mean symmetric "
          "distance; Time = report.json time_s.\n";
    for (const auto& t : titles) {
      os << "\n## " << t[1] << " (referee)\n\n";
      referee_table(os, ref, pose_of, t[0]);
    }
    agreement(os, runs, ref);
  }
  return os.str();
}

}  // namespace breastfit::experiments
