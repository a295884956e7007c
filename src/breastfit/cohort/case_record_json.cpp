#include "breastfit/cohort/case_record_json.h"

#include "breastfit/core/errors.h"

namespace breastfit::cohort {
namespace {

using nlohmann::json;

json opt(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

/// j[path...] as a number, nullopt when absent or not a number.
std::optional<double> number_at(const json& j, std::initializer_list<const char*> path) {
  const json* p = &j;
  for (const char* key : path) {
    if (!p->is_object() || !p->contains(key)) return std::nullopt;
    p = &(*p)[key];
  }
  return p->is_number() ? std::optional<double>(p->get<double>()) : std::nullopt;
}

/// The record's optional numbers with their JSON names, for both directions.
template <class Record, class F>
void for_each_number(Record& r, F&& f) {
  f("time_s", r.time_s);
  f("wall_s", r.wall_s);
  f("surface_mae_mm", r.surface_mae_mm);
  f("surface_max_mm", r.surface_max_mm);
  f("landmark_mae_mm", r.landmark_mae_mm);
  f("landmark_max_mm", r.landmark_max_mm);
  f("volume_right_ml", r.volume_right_ml);
  f("volume_left_ml", r.volume_left_ml);
  f("volume_ratio", r.volume_ratio);
  f("notch_to_nipple_right_mm", r.notch_to_nipple_right_mm);
  f("notch_to_nipple_left_mm", r.notch_to_nipple_left_mm);
  f("nipple_to_imf_right_mm", r.nipple_to_imf_right_mm);
  f("nipple_to_imf_left_mm", r.nipple_to_imf_left_mm);
  f("inter_nipple_mm", r.inter_nipple_mm);
}

}  // namespace

json to_json(const CaseRecord& r) {
  json j = {{"name", r.name}, {"scan", r.scan}, {"status", r.status}, {"resumed", r.resumed},
            {"message", r.message}, {"warnings", r.warnings}};
  j["iterations"] = r.iterations ? json(*r.iterations) : json(nullptr);
  for_each_number(r, [&](const char* key, const std::optional<double>& v) { j[key] = opt(v); });
  return j;
}

CaseRecord case_record_from_json(const json& j) {
  if (!j.is_object() || !j.contains("name") || !j["name"].is_string() || !j.contains("status") ||
      !j["status"].is_string())
    throw InvalidInput("case record: an object with a string \"name\" and \"status\" expected");
  try {
    CaseRecord r;
    r.name = j["name"].get<std::string>();
    r.status = j["status"].get<std::string>();
    r.scan = j.value("scan", "");
    r.resumed = j.value("resumed", false);
    r.message = j.value("message", "");
    r.warnings = j.value("warnings", 0);
    if (j.contains("iterations") && j["iterations"].is_number()) r.iterations = j["iterations"].get<int>();
    for_each_number(r, [&](const char* key, std::optional<double>& v) { v = number_at(j, {key}); });
    return r;
  } catch (const json::exception& e) {
    throw InvalidInput("case record '" + j["name"].get<std::string>() + "': " + e.what());
  }
}

CaseRecord case_record_from_report(const std::string& name, const std::string& scan, const json& report) {
  if (!report.is_object() || !report.contains("status") || !report["status"].is_string())
    throw InvalidInput("report.json: no \"status\"");
  CaseRecord r;
  r.name = name;
  r.scan = scan;
  r.status = report["status"].get<std::string>();
  if (!r.finished()) throw InvalidInput("report.json: unknown status '" + r.status + "'");
  if (r.status == "not_usable") r.message = report.value("verdict", std::string("not usable"));
  if (r.status == "implausible" && report.contains("plausibility") && report["plausibility"].is_object())
    for (const auto& p : report["plausibility"].value("problems", json::array()))
      if (p.is_string()) r.message += std::string(r.message.empty() ? "" : "; ") + p.get<std::string>();
  r.time_s = number_at(report, {"time_s"});
  if (const auto it = number_at(report, {"iterations"})) r.iterations = static_cast<int>(*it);
  r.surface_mae_mm = number_at(report, {"table1", "surface_mm", "mae"});
  r.surface_max_mm = number_at(report, {"table1", "surface_mm", "max"});
  // No landmarks given: the statistics are over no points (n = 0), not zero errors.
  if (number_at(report, {"table1", "landmarks_mm", "n"}).value_or(0) > 0) {
    r.landmark_mae_mm = number_at(report, {"table1", "landmarks_mm", "mae"});
    r.landmark_max_mm = number_at(report, {"table1", "landmarks_mm", "max"});
  }
  r.volume_right_ml = number_at(report, {"breast_measurements", "right", "volume_ml"});
  r.volume_left_ml = number_at(report, {"breast_measurements", "left", "volume_ml"});
  r.volume_ratio = number_at(report, {"breast_measurements", "symmetry_left_over_right", "volume"});
  r.notch_to_nipple_right_mm = number_at(report, {"breast_measurements", "right", "notch_to_nipple_mm"});
  r.notch_to_nipple_left_mm = number_at(report, {"breast_measurements", "left", "notch_to_nipple_mm"});
  r.nipple_to_imf_right_mm = number_at(report, {"breast_measurements", "right", "nipple_to_imf_mm"});
  r.nipple_to_imf_left_mm = number_at(report, {"breast_measurements", "left", "nipple_to_imf_mm"});
  r.inter_nipple_mm = number_at(report, {"breast_measurements", "inter_nipple_mm"});
  if (report.contains("warnings") && report["warnings"].is_array()) r.warnings = static_cast<int>(report["warnings"].size());
  return r;
}

}  // namespace breastfit::cohort
