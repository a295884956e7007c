#include "breastfit/cohort/cohort_csv.h"

#include <cstdio>

namespace breastfit::cohort {
namespace {

std::string quoted(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"') out += '"';
    out += ch;
  }
  return out + "\"";
}

std::string number(const std::optional<double>& v, const char* format = "%.6g") {
  if (!v) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, *v);
  return buf;
}

}  // namespace

std::vector<std::string> cohort_csv_columns() {
  return {"case",           "status",          "resumed",         "time_s",
          "wall_s",         "iterations",      "surface_mae_mm",  "surface_max_mm",
          "landmark_mae_mm", "landmark_max_mm", "volume_right_ml", "volume_left_ml",
          "volume_ratio_left_over_right", "notch_to_nipple_right_mm", "notch_to_nipple_left_mm",
          "nipple_to_imf_right_mm", "nipple_to_imf_left_mm", "inter_nipple_mm", "warnings",
          "scan",           "message"};
}

std::string format_cohort_csv(const std::vector<CaseRecord>& records) {
  std::string out;
  const auto columns = cohort_csv_columns();
  for (size_t i = 0; i < columns.size(); ++i) out += (i ? "," : "") + columns[i];
  out += "\n";
  for (const CaseRecord& r : records) {
    const std::vector<std::string> fields = {
        quoted(r.name),
        r.status,
        r.resumed ? "yes" : "no",
        number(r.time_s, "%.4f"),
        number(r.wall_s, "%.4f"),
        r.iterations ? std::to_string(*r.iterations) : "",
        number(r.surface_mae_mm),
        number(r.surface_max_mm),
        number(r.landmark_mae_mm),
        number(r.landmark_max_mm),
        number(r.volume_right_ml),
        number(r.volume_left_ml),
        number(r.volume_ratio),
        number(r.notch_to_nipple_right_mm),
        number(r.notch_to_nipple_left_mm),
        number(r.nipple_to_imf_right_mm),
        number(r.nipple_to_imf_left_mm),
        number(r.inter_nipple_mm),
        std::to_string(r.warnings),
        quoted(r.scan),
        quoted(r.message)};
    for (size_t i = 0; i < fields.size(); ++i) out += (i ? "," : "") + fields[i];
    out += "\n";
  }
  return out;
}

}  // namespace breastfit::cohort
