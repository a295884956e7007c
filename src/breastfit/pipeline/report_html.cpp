#include "breastfit/pipeline/report_html.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string_view>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/units.h"
#include "breastfit/pipeline/curve_confidence.h"
#include "breastfit/pipeline/data_uri.h"
#include "breastfit/pipeline/provenance_json.h"

namespace breastfit::pipeline {
namespace {

/// A number with a fixed number of decimals ("—" when not finite).
std::string num(double v, int decimals) {
  if (!std::isfinite(v)) return "&mdash;";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}
std::string num(const std::optional<double>& v, int decimals) { return v ? num(*v, decimals) : "&mdash;"; }
std::string percent(double fraction) { return num(100.0 * fraction, 0) + " %"; }

std::string hex(render::Rgb c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c.r, c.g, c.b);
  return buf;
}


constexpr std::string_view kStyle = R"(
body { font-family: "Helvetica Neue", Arial, sans-serif; color: #1e1e1e; max-width: 1000px; margin: 1.5em auto;
       padding: 0 1em; line-height: 1.45; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; }
h2 { font-size: 1.25em; margin-top: 1.6em; border-bottom: 1px solid #ccc; padding-bottom: 0.15em; }
table { border-collapse: collapse; margin: 0.6em 0; }
th, td { border: 1px solid #c8c8c8; padding: 0.25em 0.6em; text-align: left; vertical-align: top; }
th { background: #f0f0f0; font-weight: 600; }
td.n { text-align: right; font-variant-numeric: tabular-nums; }
table.meta th { width: 9em; }
.box { border-radius: 6px; padding: 0.6em 1em; margin: 1em 0; }
.warnings { background: #fff1cc; border: 2px solid #e0a000; }
.warnings h2 { border: none; margin: 0.1em 0 0.3em 0; color: #7a4d00; }
.failed { background: #fde2e1; border: 2px solid #c62828; }
.failed h2 { color: #8e1b1b; }
.clean { background: #e6f4ea; border: 2px solid #2e7d32; }
.badge { display: inline-block; min-width: 3.2em; text-align: center; border-radius: 4px; padding: 0 0.4em;
         font-weight: 600; color: #fff; }
.high { background: #2e7d32; } .check { background: #d08700; } .low { background: #c62828; }
.swatch { display: inline-block; width: 1.6em; height: 0.5em; vertical-align: middle; border-radius: 2px; }
.note { color: #555; font-size: 0.92em; }
figure { margin: 1em 0; }
.grid { display: grid; grid-template-columns: repeat(auto-fit, minmax(300px, 1fr)); gap: 0 1em; }
.grid figure img { max-width: 100%; }
code.hash { font-size: 0.85em; word-break: break-all; }
details { margin: 0.6em 0; } summary { cursor: pointer; }
pre { background: #f4f4f4; padding: 0.6em; font-size: 0.85em; max-height: 40em; overflow: auto; }
figure img { width: 100%; max-width: 900px; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 0.95em; color: #333; max-width: 900px; }
code { background: #f4f4f4; padding: 0 0.2em; }
@media print { figure { page-break-inside: avoid; } body { max-width: none; } }
)";

void row(std::string& h, std::string_view label, const std::string& value) {
  h += "<tr><th>";
  h += label;
  h += "</th><td>" + value + "</td></tr>\n";
}

void header(std::string& h, const RegisterResult& r, const std::string& template_name) {
  h += "<h1>Registration report</h1>\n";
  h += "<p class=\"note\">breastfit: the rigged template torso registered to the patient's 3D surface scan, "
       "and the template's surgical drawings transferred onto the scan.</p>\n";
  h += "<table class=\"meta\">\n";
  row(h, "Scan", "<code>" + html_escape(r.scan_name) + "</code>");
  row(h, "Template", html_escape(template_name));
  const std::string units = r.scan.units == mesh::Units::Metres
                                ? "metres (converted: every number in this report is in millimetres)"
                                : "millimetres";
  row(h, "Scan units", units);
  const auto& m = r.scan.mesh_mm;
  row(h, "Scan type",
      r.scan.was_point_cloud
          ? "point cloud (registered as small oriented discs)"
          : "triangle mesh, " + std::to_string(m.V.rows()) + " vertices, " + std::to_string(m.F.rows()) + " triangles");
  row(h, "Status",
      !r.usable()                 ? "<b>not usable</b>: " + html_escape(r.fit.summary.message)
      : r.plausibility.plausible ? std::string("registered")
                                 : std::string("<b>implausible</b>: registered, but the fit does not look like this torso (see below)"));
  h += "</table>\n";
}

void warnings_box(std::string& h, const RegisterResult& r) {
  std::vector<std::string> all = r.warnings;
  for (const auto& w : r.breasts.warnings) all.push_back("breast measurements: " + w);
  if (!r.usable()) {
    h += "<div class=\"box failed\"><h2>The registration is not usable</h2><p>" +
         html_escape(r.fit.summary.verdict.reason) + ". Do not use the drawings or measurements of this report.</p></div>\n";
  } else if (!r.plausibility.plausible) {
    h += "<div class=\"box failed\"><h2>The fit is implausible</h2><ul>\n";
    for (const auto& p : r.plausibility.problems) h += "<li>" + html_escape(p) + "</li>\n";
    h += "</ul><p>Check the scan, its units and the template before using the drawings or measurements.</p></div>\n";
  }
  if (all.empty()) {
    h += "<div class=\"box clean\"><b>No warnings.</b></div>\n";
    return;
  }
  h += "<div class=\"box warnings\"><h2>&#9888; Warnings (" + std::to_string(all.size()) + ")</h2>\n<ul>\n";
  for (const auto& w : all) h += "<li>" + html_escape(w) + "</li>\n";
  h += "</ul></div>\n";
}

void how_to_read(std::string& h) {
  h += "<h2>How to read this report</h2>\n<p>The template (a generic female torso with expert drawings) was "
       "deformed to match the scan; its landmarks should sit on the landmarks placed on the scan and its "
       "surface on the scan's surface. The <b>surface error</b> is the distance from each point of the "
       "fitted model to the scan (a few millimetres is typical of a good fit of a noisy handheld scan); the "
       "<b>landmark error</b> is the distance between each fitted landmark and the one placed on the scan. "
       "The drawings (breast contours, inframammary folds, sternum) are the template's, carried onto the "
       "scan: they are a starting point to be checked and adjusted, not a plan. Each drawing's "
       "<b>confidence</b> says how much of it lies on the scan and how closely the model follows the scan "
       "along it; in the figures the pale thin parts of a drawing pass over holes of the scan and follow the "
       "fitted model instead. Distances are straight lines in millimetres; volumes are relative (see the "
       "measurements). All numbers are in millimetres unless stated.</p>\n";
}

/// How the solver ended, for a reader: "converged" when a convergence test stopped it; at the
/// last stage's iteration cap "finished its iteration schedule" with the last step's relative
/// energy change (how settled it was) — a cap is the schedule's end, not a failure (the verdict
/// says whether the fit is usable); the per-stage endings as a detail.
std::string solver_text(const fit::FitSummary& s) {
  std::string head;
  if (s.converged()) {
    head = "<b>converged</b> (" + std::string(fit::to_string(s.termination)) + ")";
  } else if (s.termination == fit::Termination::IterationCap) {
    head = "<b>finished its iteration schedule</b>";
    if (!s.iterations.empty() && s.iterations.back().energy_before > 0) {
      const auto& it = s.iterations.back();
      head += " (its last step changed the energy by " +
              num(100.0 * (it.energy_after - it.energy_before) / it.energy_before, 2) + " %)";
    }
  } else {
    head = "<b>" + html_escape(s.termination_message) + "</b>";
  }
  std::string stages;
  for (const auto& st : s.stages)
    stages += (stages.empty() ? "" : "; ") + html_escape(st.name) + " " + std::to_string(st.iterations) + " (" +
              (fit::is_convergence(st.termination) ? std::string("converged")
               : st.termination == fit::Termination::IterationCap ? std::string("its cap")
                                                                   : std::string(fit::to_string(st.termination))) +
              ")";
  return head + "<br><span class=\"note\">" + html_escape(s.termination_message) +
         (stages.empty() ? "" : ". Iterations per stage: " + stages + ".") + "</span>";
}

void registration_table(std::string& h, const RegisterResult& r, const ReportFigures& figures) {
  const auto& s = r.fit.summary;
  h += "<h2>Summary</h2>\n<table>\n";
  row(h, "Registration time", num(r.time_s, 2) + " s");
  std::string stages;
  for (const auto& st : s.stages)
    stages += (stages.empty() ? "" : ", ") + html_escape(st.name) + " " + std::to_string(st.iterations);
  row(h, "Iterations", std::to_string(s.iterations.size()) + (stages.empty() ? "" : " (" + stages + ")"));
  row(h, "Verdict", html_escape(s.verdict.reason));
  row(h, "Solver", solver_text(s));
  row(h, "Initialisation",
      html_escape(s.initialization) + ", " + std::to_string(s.landmarks_used) + " landmark" +
          (s.landmarks_used == 1 ? "" : "s") + " used" +
          (s.initialization_detail.empty() ? "" : "<br><span class=\"note\">" + html_escape(s.initialization_detail) + "</span>"));
  const auto& e = r.surface;
  row(h, "Surface error",
      "MAE <b>" + num(e.mae, 2) + " mm</b>, SD " + num(e.sd, 2) + " mm, max " + num(e.max, 1) + " mm <span class=\"note\">(" +
          std::to_string(e.n) + " of " + std::to_string(r.fitted_mm.V.rows()) +
          " fitted vertices compared: the part the scan covers; the others face holes, lie beyond the scanned "
          "area or farther than " + num(r.coverage.options.max_distance_mm, 0) + " mm from it)</span>");
  row(h, "Scan coverage",
      percent(r.coverage.fraction()) + " of the fitted model <span class=\"note\">(grey in the distance figure: "
      "not covered, not counted)</span>");
  if (s.detail.applied) {
    const auto& m = r.surface_model_only;
    row(h, "Template alone",
        "MAE <b>" + num(m.mae, 2) + " mm</b>, SD " + num(m.sd, 2) + " mm, max " + num(m.max, 1) +
            " mm <span class=\"note\">(the posed template before the surface detail: how far its shape space "
            "reaches this body; the detail then moved the surface along its normals by " +
            num(s.detail.mean_abs_mm, 1) + " mm on average, at most " + num(s.detail.max_abs_mm, 1) +
            " mm. The drawings follow the template, so this is the number to judge them by.)</span>");
  }
  int compared = 0, within2 = 0, within5 = 0;
  for (Eigen::Index i = 0; i < figures.distances_mm.size(); ++i) {
    const double d = figures.distances_mm[i];
    if (!std::isfinite(d)) continue;
    ++compared;
    within2 += d <= 2.0;
    within5 += d <= 5.0;
  }
  if (compared > 0)
    row(h, "Fitted surface near the scan",
        percent(static_cast<double>(within2) / compared) + " within 2 mm, " +
            percent(static_cast<double>(within5) / compared) + " within 5 mm");
  const auto& l = r.landmarks.stats;
  if (l.n > 0)
    row(h, "Landmark error",
        "MAE <b>" + num(l.mae, 2) + " mm</b>, SD " + num(l.sd, 2) + " mm, max " + num(l.max, 1) + " mm, min " +
            num(l.min, 1) + " mm <span class=\"note\">(" + std::to_string(l.n) + " landmarks)</span>");
  else
    row(h, "Landmark error", "no landmarks were given: not measured");
  h += "</table>\n";
}

void landmarks_table(std::string& h, const RegisterResult& r) {
  if (r.landmarks.names.empty()) return;
  h += "<h2>Landmarks</h2>\n<p class=\"note\">Distance between each fitted landmark and the landmark given on the "
       "scan. A landmark farther than its tolerance (15 mm; 30 mm for the mid-axillary points, which mark a line "
       "on skin that slides with the arm, weighted 0.1 in the fit: errors of 10&ndash;20 mm along the line are "
       "usual) is marked: check its placement on the scan. The fit gives such a landmark less weight. Each "
       "landmark is also compared with where the scan's anatomy and the other landmarks put it (a fit without "
       "it): one farther than its tolerance there is marked and down-weighted too.</p>\n<table>\n"
       "<tr><th>landmark</th><th>error (mm)</th><th>tolerance (mm)</th><th></th></tr>\n";
  for (size_t i = 0; i < r.landmarks.names.size(); ++i) {
    const double d = r.landmarks.distances_mm[i];
    const fit::LandmarkCheck* check = nullptr;
    for (const auto& c : r.fit.summary.landmark_checks)
      if (c.name == r.landmarks.names[i]) check = &c;
    h += "<tr><td>" + html_escape(r.landmarks.names[i]) + "</td><td class=\"n\">" + num(d, 1) + "</td><td class=\"n\">" +
         (check ? num(check->tolerance_mm, 0) : std::string("&mdash;")) + "</td><td>" +
         (check && check->flagged
              ? "<span class=\"badge check\">check</span> <span class=\"note\">" +
                    (check->predicted_distance_mm > check->predicted_tolerance_mm
                         ? num(check->predicted_distance_mm, 0) +
                               " mm from where the scan's anatomy and the other landmarks put it"
                     : check->distance_mm > check->tolerance_mm || check->anatomy.empty()
                         ? "beyond " + num(check->tolerance_mm, 0) + " mm"
                         : num(check->anatomy_distance_mm, 0) + " mm from " + html_escape(check->anatomy)) +
                    (check->factor < 1 ? "; down-weighted" : "") + "</span>"
              : "") +
         "</td></tr>\n";
  }
  h += "</table>\n";
}

void drawings_table(std::string& h, const RegisterResult& r) {
  h += "<h2>Transferred drawings</h2>\n";
  if (r.drawings_on_scan.empty()) {
    h += "<p>The template has no drawings.</p>\n";
    return;
  }
  h += "<table>\n<tr><th></th><th>drawing</th><th>length (mm)</th><th>on the scan</th>"
       "<th>mean model-to-scan (mm)</th><th>confidence</th></tr>\n";
  for (size_t k = 0; k < r.drawings_on_scan.size(); ++k) {
    const auto& c = r.drawings_on_scan[k];
    const std::string_view conf = confidence_name(curve_confidence(c));
    h += "<tr><td><span class=\"swatch\" style=\"background:" + hex(report_curve_colour(c.name, k)) + "\"></span></td><td>" +
         html_escape(c.name) + (c.closed ? " <span class=\"note\">(closed)</span>" : "") + "</td><td class=\"n\">" +
         num(c.length_mm, 1) + "</td><td class=\"n\">" + percent(c.supported_fraction) + "</td><td class=\"n\">" +
         num(c.mean_model_to_scan_mm, 1) + "</td><td><span class=\"badge " + std::string(conf) + "\">" +
         std::string(conf) + "</span></td></tr>\n";
  }
  h += "</table>\n<p class=\"note\">Confidence &mdash; " + html_escape(curve_confidence_rule()) +
       " &ldquo;On the scan&rdquo;: the share of the curve with scan surface under it (within 10 mm, not on the "
       "rim of a hole); elsewhere the curve follows the fitted model. &ldquo;Mean model-to-scan&rdquo;: how far "
       "the fitted model is from the scan along the curve, i.e. how much the transfer moved it.</p>\n";
}

void measurements_table(std::string& h, const RegisterResult& r) {
  const auto& b = r.breasts;
  h += "<h2>Breast measurements</h2>\n<table>\n<tr><th></th><th>right</th><th>left</th><th>left / right</th></tr>\n";
  h += "<tr><th>volume (ml)</th><td class=\"n\">" + num(b.right.volume_ml, 0) + "</td><td class=\"n\">" +
       num(b.left.volume_ml, 0) + "</td><td class=\"n\">" + num(b.volume_ratio, 2) + "</td></tr>\n";
  h += "<tr><th>sternal notch &ndash; nipple (mm)</th><td class=\"n\">" + num(b.right.notch_to_nipple_mm, 1) +
       "</td><td class=\"n\">" + num(b.left.notch_to_nipple_mm, 1) + "</td><td class=\"n\">" +
       num(b.notch_to_nipple_ratio, 2) + "</td></tr>\n";
  h += "<tr><th>nipple &ndash; inframammary fold (mm)</th><td class=\"n\">" + num(b.right.nipple_to_imf_mm, 1) +
       "</td><td class=\"n\">" + num(b.left.nipple_to_imf_mm, 1) + "</td><td class=\"n\">" +
       num(b.nipple_to_imf_ratio, 2) + "</td></tr>\n";
  h += "<tr><th>inter-nipple (mm)</th><td class=\"n\" colspan=\"3\">" + num(b.inter_nipple_mm, 1) + "</td></tr>\n";
  h += "</table>\n<p class=\"note\">Measured on the fitted model: straight-line distances; the fold's point is its "
       "lowest point. <b>Volumes are relative</b>: the solid between the skin of the template's breast region and a "
       "membrane spanning its border. Use them to compare left with right, or one patient over time with the same "
       "template, not as absolute implant or resection volumes.</p>\n";
  if (!b.warnings.empty()) {
    h += "<ul class=\"note\">\n";
    for (const auto& w : b.warnings) h += "<li>" + html_escape(w) + "</li>\n";
    h += "</ul>\n";
  }
}

void figures_section(std::string& h, const ReportFigures& figures) {
  if (figures.figures.empty()) return;
  h += "<h2>Figures</h2>\n<p class=\"note\">Views oriented by the fitted model's anatomy (" +
       html_escape(figures.body_frame) +
       "). In front views the patient's right is on the left of the image (letters R and L at the sides).</p>\n";
  // Full-width figures alone; the smaller (side) figures two to a row.
  const int full = figures.figures.front().image.width();
  int number = 0;
  bool in_grid = false;
  for (const auto& f : figures.figures) {
    const bool small = f.image.width() < full;
    if (small && !in_grid) h += "<div class=\"grid\">\n";
    if (!small && in_grid) h += "</div>\n";
    in_grid = small;
    h += "<figure id=\"fig-" + html_escape(f.id) + "\"><img src=\"" + data_uri("image/png", f.png.empty() ? f.image.encode_png() : f.png) +
         "\" width=\"" + std::to_string(f.image.width()) + "\" height=\"" + std::to_string(f.image.height()) +
         "\" alt=\"" + html_escape(f.title) + "\">\n<figcaption><b>Figure " + std::to_string(++number) + ".</b> " +
         html_escape(f.caption) + "</figcaption></figure>\n";
  }
  if (in_grid) h += "</div>\n";
}

void provenance_section(std::string& h, const RegisterResult& r) {
  h += "<h2 id=\"provenance\">Traceability</h2>\n";
  if (!r.provenance) {
    h += "<p class=\"note\">Not recorded for this registration (it was not run from files).</p>\n";
    return;
  }
  const Provenance& p = *r.provenance;
  h += "<p class=\"note\">What this registration read and how it ran (the same as report.json's "
       "<code>provenance</code> and <code>run</code> blocks). Compare the SHA-256 of a file with "
       "<code>sha256sum FILE</code> to check it is the one used.</p>\n<table class=\"meta\">\n";
  row(h, "breastfit", html_escape(p.version));
  for (const InputFile& f : p.inputs)
    row(h, f.role, "<code>" + html_escape(f.path) + "</code><br><span class=\"note\">SHA-256</span> <code class=\"hash\">" +
                       html_escape(f.sha256) + "</code>");
  h += "</table>\n<table class=\"meta\">\n<tbody class=\"run\">\n";
  row(h, "Started (UTC)", html_escape(p.started_utc));
  row(h, "Command line", "<code>" + html_escape(p.command_line) + "</code>");
  h += "</tbody>\n</table>\n<details><summary>Effective fit options (every weight, threshold and stage; usable as "
       "<code>--config</code> to repeat the fit)</summary>\n<pre>" +
       html_escape(provenance_json(p)["fit_options"].dump(2)) + "</pre></details>\n";
}

void files_section(std::string& h) {
  h += "<h2>Files in this folder</h2>\n<p class=\"note\">All in the scan's coordinate frame and units, so they "
       "overlay the scan directly. In 3D Slicer: drag the scan, <code>fitted.ply</code> and the "
       "<code>.mrk.json</code> files into the window.</p>\n<table>\n<tr><th>file</th><th>what</th><th>open with</th></tr>\n";
  const std::pair<const char*, const char*> files[] = {
      {"report.html", "this report</td><td>any web browser (works offline)"},
      {"drawings.mrk.json", "the transferred drawings as curves (contours closed)</td><td>3D Slicer (Markups)"},
      {"landmarks.mrk.json", "the fitted model's landmarks</td><td>3D Slicer (Markups)"},
      {"fitted.ply", "the fitted model (the template deformed to the scan)</td><td>3D Slicer, MeshLab, CloudCompare"},
      {"scan_painted.ply", "the scan with the drawings painted into its colours</td><td>MeshLab, CloudCompare, 3D Slicer"},
      {"drawings.ply, drawings.obj", "the drawings as polylines</td><td>MeshLab, CloudCompare, Blender"},
      {"report.json", "every number of this report and the solver's details</td><td>a text editor, scripts"},
      {"params.json", "the fitted template parameters (pose, bone scales, shape weights)</td><td>breastfit map"},
  };
  for (const auto& [name, what] : files) h += "<tr><td><code>" + std::string(name) + "</code></td><td>" + what + "</td></tr>\n";
  h += "</table>\n";
}

}  // namespace

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string report_html(const RegisterResult& r, const std::string& template_name, const ReportFigures& figures) {
  std::string h;
  h.reserve(1 << 20);
  h += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>Registration report: " +
       html_escape(r.scan_name) + "</title>\n<style>" + std::string(kStyle) + "</style>\n</head>\n<body>\n";
  header(h, r, template_name);
  warnings_box(h, r);
  how_to_read(h);
  registration_table(h, r, figures);
  drawings_table(h, r);
  measurements_table(h, r);
  figures_section(h, figures);
  landmarks_table(h, r);
  files_section(h);
  provenance_section(h, r);
  h += "</body>\n</html>\n";
  return h;
}

void write_report_html(const std::filesystem::path& path, const RegisterResult& r, const model::RiggedModel& model,
                       const ReportFigureOptions& options, const std::shared_ptr<ReportLayerDrawing>& layers) {
  const std::string html = report_html(r, model.name, report_figures(r, model, options, layers));
  std::ofstream f(path, std::ios::binary);
  if (!f) throw IoError(path.string(), "cannot open for writing");
  f << html;
  if (!f) throw IoError(path.string(), "write failed (disk full?)");
}

}  // namespace breastfit::pipeline
