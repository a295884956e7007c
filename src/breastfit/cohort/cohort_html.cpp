#include "breastfit/cohort/cohort_html.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>

#include "breastfit/pipeline/report_html.h"

namespace breastfit::cohort {
namespace {

using pipeline::html_escape;

struct Metric {
  const char* key;    ///< CSV column
  const char* title;  ///< plot title
  std::function<std::optional<double>(const CaseRecord&)> get;
};

const std::vector<Metric>& metrics() {
  static const std::vector<Metric> m = {
      {"surface_mae_mm", "Surface error (fitted → scan), mean, mm", [](const CaseRecord& r) { return r.surface_mae_mm; }},
      {"landmark_mae_mm", "Landmark error, mean, mm", [](const CaseRecord& r) { return r.landmark_mae_mm; }},
      {"time_s", "Registration time, s", [](const CaseRecord& r) { return r.time_s; }},
      {"volume_right_ml", "Right breast volume, ml", [](const CaseRecord& r) { return r.volume_right_ml; }},
      {"volume_left_ml", "Left breast volume, ml", [](const CaseRecord& r) { return r.volume_left_ml; }},
  };
  return m;
}

std::string fmt(double v, const char* format = "%.3g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// (name, value) of the ok cases that have the metric.
std::vector<std::pair<std::string, double>> values_of(const std::vector<CaseRecord>& records, const Metric& m) {
  std::vector<std::pair<std::string, double>> out;
  for (const CaseRecord& r : records)
    if (r.status == "ok")
      if (const auto v = m.get(r); v && std::isfinite(*v)) out.emplace_back(r.name, *v);
  return out;
}

/// A histogram of `values` as an inline SVG (bars, counts above them, the range below).
std::string histogram_svg(const std::string& title, const std::vector<double>& values) {
  constexpr int kW = 360, kH = 210, kLeft = 30, kBottom = 36, kTop = 38, kBins = 12;
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(kW) + "\" height=\"" +
                    std::to_string(kH) + "\" role=\"img\"><title>" + html_escape(title) + "</title>";
  svg += "<text x=\"" + std::to_string(kW / 2) + "\" y=\"16\" text-anchor=\"middle\" class=\"t\">" + html_escape(title) +
         "</text>";
  if (values.empty()) return svg + "<text x=\"" + std::to_string(kW / 2) + "\" y=\"100\" text-anchor=\"middle\">no values</text></svg>";
  const auto [lo_it, hi_it] = std::minmax_element(values.begin(), values.end());
  double lo = *lo_it, hi = *hi_it;
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) {  // one value: a bin around it
    lo -= 0.5 * std::max(1e-3, std::abs(lo) * 0.1);
    hi += 0.5 * std::max(1e-3, std::abs(hi) * 0.1);
  }
  std::vector<int> counts(kBins, 0);
  for (double v : values) counts[std::min(kBins - 1, static_cast<int>((v - lo) / (hi - lo) * kBins))]++;
  const int peak = *std::max_element(counts.begin(), counts.end());
  const double plot_w = kW - kLeft - 10, plot_h = kH - kTop - kBottom, bar_w = plot_w / kBins;
  for (int b = 0; b < kBins; ++b) {
    if (!counts[b]) continue;
    const double h = plot_h * counts[b] / peak, x = kLeft + b * bar_w, y = kTop + plot_h - h;
    svg += "<rect x=\"" + fmt(x, "%.1f") + "\" y=\"" + fmt(y, "%.1f") + "\" width=\"" + fmt(bar_w - 2, "%.1f") +
           "\" height=\"" + fmt(h, "%.1f") + "\" class=\"bar\"/>";
    svg += "<text x=\"" + fmt(x + bar_w / 2, "%.1f") + "\" y=\"" + fmt(y - 3, "%.1f") +
           "\" text-anchor=\"middle\" class=\"c\">" + std::to_string(counts[b]) + "</text>";
  }
  const double axis_y = kTop + plot_h;
  svg += "<line x1=\"" + std::to_string(kLeft) + "\" y1=\"" + fmt(axis_y, "%.1f") + "\" x2=\"" +
         fmt(kLeft + plot_w, "%.1f") + "\" y2=\"" + fmt(axis_y, "%.1f") + "\" class=\"axis\"/>";
  svg += "<text x=\"" + std::to_string(kLeft) + "\" y=\"" + fmt(axis_y + 16, "%.1f") + "\">" + fmt(lo) + "</text>";
  svg += "<text x=\"" + fmt(kLeft + plot_w, "%.1f") + "\" y=\"" + fmt(axis_y + 16, "%.1f") + "\" text-anchor=\"end\">" +
         fmt(hi) + "</text>";
  svg += "<text x=\"" + fmt(kLeft + plot_w / 2, "%.1f") + "\" y=\"" + fmt(axis_y + 30, "%.1f") +
         "\" text-anchor=\"middle\" class=\"c\">n = " + std::to_string(values.size()) + ", median " +
         fmt(median(values)) + "</text>";
  return svg + "</svg>";
}

std::string cell(const std::optional<double>& v, const char* format = "%.2f") { return v ? fmt(*v, format) : ""; }

}  // namespace

std::vector<Outlier> find_outliers(const std::vector<CaseRecord>& records) {
  std::vector<Outlier> out;
  for (const Metric& m : metrics()) {
    const auto named = values_of(records, m);
    if (named.size() < 4) continue;
    std::vector<double> v;
    for (const auto& [name, x] : named) v.push_back(x);
    const double med = median(v);
    std::vector<double> dev;
    for (double x : v) dev.push_back(std::abs(x - med));
    const double scale = 1.4826 * median(dev);
    if (scale <= 0) continue;
    std::vector<Outlier> these;
    for (const auto& [name, x] : named)
      if (const double z = (x - med) / scale; std::abs(z) > 3) these.push_back({name, m.key, x, z});
    std::stable_sort(these.begin(), these.end(),
                     [](const Outlier& a, const Outlier& b) { return std::abs(a.robust_z) > std::abs(b.robust_z); });
    out.insert(out.end(), these.begin(), these.end());
  }
  return out;
}

std::string cohort_html(const std::vector<CaseRecord>& records) {
  int ok = 0, implausible = 0, not_usable = 0, failed = 0, resumed = 0;
  for (const CaseRecord& r : records) {
    ok += r.status == "ok";
    implausible += r.status == "implausible";
    not_usable += r.status == "not_usable";
    failed += r.status == "failed";
    resumed += r.resumed;
  }
  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>breastfit cohort</title><style>"
      "body{font-family:sans-serif;margin:1.5em;color:#222}table{border-collapse:collapse;font-size:0.9em}"
      "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}td.l,th.l{text-align:left}"
      ".failed{background:#fdd}.not_usable{background:#ffe6bf}.implausible{background:#ffe6bf}.plots{display:flex;flex-wrap:wrap;gap:12px}"
      "svg{border:1px solid #ddd;background:#fafafa}svg text{font-size:11px}svg .t{font-size:12px;font-weight:bold}"
      "svg .bar{fill:#4a7ab5}svg .axis{stroke:#444}svg .c{fill:#444}"
      "</style></head><body>\n<h1>breastfit cohort</h1>\n";
  h += "<p>" + std::to_string(records.size()) + " cases: <b>" + std::to_string(ok) + " ok</b>, " +
       (implausible > 0 ? std::to_string(implausible) + " implausible, " : std::string()) +
       std::to_string(not_usable) + " not usable, " + std::to_string(failed) + " failed (" + std::to_string(resumed) +
       " taken from a previous run). Each case's outputs are in its sub-directory; the numbers are in "
       "<a href=\"cohort.csv\">cohort.csv</a>.</p>\n";

  h += "<h2>Distributions (ok cases)</h2>\n<div class=\"plots\">";
  for (const Metric& m : metrics()) {
    std::vector<double> v;
    for (const auto& [name, x] : values_of(records, m)) v.push_back(x);
    h += histogram_svg(m.title, v);
  }
  h += "</div>\n";

  h += "<h2>Outliers</h2>\n";
  const auto outliers = find_outliers(records);
  if (outliers.empty()) {
    h += "<p>None (robust z = (x − median) / (1.4826 MAD) above 3).</p>\n";
  } else {
    h += "<p>Values with a robust z = (x − median) / (1.4826 MAD) above 3 in absolute value.</p>\n"
         "<table><tr><th class=\"l\">case</th><th class=\"l\">metric</th><th>value</th><th>robust z</th></tr>\n";
    for (const Outlier& o : outliers)
      h += "<tr><td class=\"l\">" + html_escape(o.name) + "</td><td class=\"l\">" + o.metric + "</td><td>" +
           fmt(o.value, "%.3f") + "</td><td>" + fmt(o.robust_z, "%.1f") + "</td></tr>\n";
    h += "</table>\n";
  }

  h += "<h2>Failed, not usable and implausible</h2>\n";
  if (failed + not_usable + implausible == 0) {
    h += "<p>None.</p>\n";
  } else {
    h += "<table><tr><th class=\"l\">case</th><th class=\"l\">status</th><th class=\"l\">reason</th></tr>\n";
    for (const CaseRecord& r : records)
      if (!(r.status == "ok"))
        h += "<tr class=\"" + r.status + "\"><td class=\"l\">" + html_escape(r.name) + "</td><td class=\"l\">" +
             r.status + "</td><td class=\"l\">" + html_escape(r.message) + "</td></tr>\n";
    h += "</table>\n";
  }

  h += "<h2>Cases</h2>\n<table><tr><th class=\"l\">case</th><th class=\"l\">status</th><th>time s</th>"
       "<th>surface mm</th><th>landmarks mm</th><th>vol R ml</th><th>vol L ml</th><th>warnings</th></tr>\n";
  for (const CaseRecord& r : records) {
    const std::string name = html_escape(r.name);
    const bool has_outputs = r.status == "ok" || r.status == "implausible";
    const std::string link = has_outputs ? "<a href=\"" + name + "/\">" + name + "</a>" : name;
    h += "<tr class=\"" + r.status + "\"><td class=\"l\">" + link + "</td><td class=\"l\">" + r.status + "</td><td>" +
         cell(r.time_s, "%.3f") + "</td><td>" + cell(r.surface_mae_mm) + "</td><td>" + cell(r.landmark_mae_mm) +
         "</td><td>" + cell(r.volume_right_ml, "%.0f") + "</td><td>" + cell(r.volume_left_ml, "%.0f") + "</td><td>" +
         std::to_string(r.warnings) + "</td></tr>\n";
  }
  h += "</table>\n</body></html>\n";
  return h;
}

}  // namespace breastfit::cohort
