// report.html on a real registration of a synthetic case: self-contained (only data: URIs),
// every curve, warning and number of the result present, warnings at the top, escaping,
// embedded images that decode to PNGs of the right size, determinism; base64 and the curve
// confidence rule.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "breastfit/core/errors.h"
#include "breastfit/pipeline/curve_confidence.h"
#include "breastfit/pipeline/data_uri.h"
#include "breastfit/pipeline/register_outputs.h"
#include "breastfit/pipeline/report_html.h"
#include "breastfit/render/image.h"
#include "pipeline/report_test_case.h"
#include "support/test_paths.h"

namespace breastfit {
namespace {

namespace fs = std::filesystem;
using pipeline::ReportFigureOptions;

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

ReportFigureOptions small_options() {
  ReportFigureOptions o;
  o.size = 320;
  o.side_size = 160;
  return o;
}

/// The figure width in the report: the front and distance views full size, the others smaller.
std::string width_of(size_t figure, int full, int side) {
  return std::to_string(figure == 0 || figure == 5 ? full : side);
}

const pipeline::ReportFigures& figures() {
  static const pipeline::ReportFigures f = [] {
    return pipeline::render_report_figures(test::report_test_result(), small_options());
  }();
  return f;
}

/// The report of the shared result with two extra warnings, one needing escaping.
const pipeline::RegisterResult& warned_result() {
  static const pipeline::RegisterResult r = [] {
    pipeline::RegisterResult copy = test::report_test_result();
    copy.warnings.push_back("landmark 'nipple_L' is 12.3 mm away from the scan surface");
    copy.warnings.push_back("a <b>bold</b> & \"quoted\" warning");
    return copy;
  }();
  return r;
}

const std::string& html() {
  static const std::string h = pipeline::report_html(warned_result(), "default torso", figures());
  return h;
}

std::vector<std::uint8_t> base64_decode(const std::string& s) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::vector<std::uint8_t> out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : s) {
    if (c == '=') break;
    const int v = value(c);
    if (v < 0) ADD_FAILURE() << "not base64: " << c;
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<std::uint8_t>((acc >> bits) & 0xff));
    }
  }
  return out;
}

/// The values of every attribute `attr="..."` in the document.
std::vector<std::string> attribute_values(const std::string& doc, const std::string& attr) {
  std::vector<std::string> out;
  const std::string key = attr + "=\"";
  for (size_t p = doc.find(key); p != std::string::npos; p = doc.find(key, p + 1)) {
    const size_t b = p + key.size(), e = doc.find('"', b);
    out.push_back(doc.substr(b, e - b));
  }
  return out;
}

TEST(Base64, MatchesRfc4648Vectors) {
  auto enc = [](const std::string& s) { return pipeline::base64_encode(std::vector<std::uint8_t>(s.begin(), s.end())); };
  EXPECT_EQ(enc(""), "");
  EXPECT_EQ(enc("f"), "Zg==");
  EXPECT_EQ(enc("fo"), "Zm8=");
  EXPECT_EQ(enc("foo"), "Zm9v");
  EXPECT_EQ(enc("foob"), "Zm9vYg==");
  EXPECT_EQ(enc("fooba"), "Zm9vYmE=");
  EXPECT_EQ(enc("foobar"), "Zm9vYmFy");
  EXPECT_EQ(pipeline::base64_encode({0xff, 0xfe, 0x00}), "//4A");
  EXPECT_EQ(pipeline::data_uri("image/png", {'h', 'i'}), "data:image/png;base64,aGk=");
}

TEST(CurveConfidence, FollowsTheStatedRule) {
  transfer::TransferredCurve c;
  auto grade = [&](double f, double d) {
    c.supported_fraction = f;
    c.mean_model_to_scan_mm = d;
    return pipeline::curve_confidence(c);
  };
  using pipeline::CurveConfidence;
  EXPECT_EQ(grade(1.0, 0.5), CurveConfidence::High);
  EXPECT_EQ(grade(0.9, 2.0), CurveConfidence::High);
  EXPECT_EQ(grade(0.89, 1.0), CurveConfidence::Check);
  EXPECT_EQ(grade(1.0, 2.1), CurveConfidence::Check);
  EXPECT_EQ(grade(0.5, 5.0), CurveConfidence::Check);
  EXPECT_EQ(grade(0.49, 1.0), CurveConfidence::Low);
  EXPECT_EQ(grade(1.0, 5.1), CurveConfidence::Low);
  EXPECT_EQ(grade(0.0, 0.0), CurveConfidence::Low);
  EXPECT_EQ(grade(NAN, 1.0), CurveConfidence::Low);
  const std::string rule = pipeline::curve_confidence_rule();
  for (const char* part : {"high", "90 %", "2 mm", "check", "50 %", "5 mm", "low"})
    EXPECT_NE(rule.find(part), std::string::npos) << part << " in " << rule;
}

TEST(ReportHtml, IsSelfContained) {
  const std::string& h = html();
  EXPECT_EQ(h.find("http://"), std::string::npos);
  EXPECT_EQ(h.find("https://"), std::string::npos);
  EXPECT_EQ(h.find("<script"), std::string::npos);
  EXPECT_EQ(h.find("<link"), std::string::npos);
  EXPECT_EQ(h.find("url("), std::string::npos);
  EXPECT_EQ(h.find("@import"), std::string::npos);
  const auto srcs = attribute_values(h, "src");
  EXPECT_EQ(srcs.size(), 6u);
  for (const auto& s : srcs) EXPECT_EQ(s.rfind("data:image/png;base64,", 0), 0u) << s.substr(0, 60);
  for (const auto& href : attribute_values(h, "href")) EXPECT_EQ(href.rfind('#', 0), 0u) << href;
  EXPECT_EQ(h.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(h.find("</html>"), std::string::npos);
}

TEST(ReportHtml, EmbedsTheFiguresAsPngsOfTheRightSize) {
  const auto srcs = attribute_values(html(), "src");
  ASSERT_EQ(srcs.size(), figures().figures.size());
  const fs::path dir = test::temp_dir();
  for (size_t i = 0; i < srcs.size(); ++i) {
    const std::string b64 = srcs[i].substr(std::string("data:image/png;base64,").size());
    const std::vector<std::uint8_t> png = base64_decode(b64);
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png[1], 'P');
    EXPECT_EQ(png[2], 'N');
    EXPECT_EQ(png[3], 'G');
    EXPECT_EQ(png, figures().figures[i].image.encode_png()) << i;
    const fs::path p = dir / ("fig" + std::to_string(i) + ".png");
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
    const render::Image img = render::read_png(p);
    EXPECT_EQ(std::to_string(img.width()), width_of(i, 320, 160)) << i;
    EXPECT_EQ(img.height(), img.width());
    EXPECT_EQ(img.bytes(), figures().figures[i].image.bytes()) << i;
  }
  const auto widths = attribute_values(html(), "width");
  ASSERT_EQ(widths.size(), 6u);
  for (size_t i = 0; i < widths.size(); ++i) EXPECT_EQ(widths[i], width_of(i, 320, 160)) << i;
  // The four side views two to a row, in one grid between the front and the distance figures.
  const size_t grid = html().find("<div class=\"grid\">");
  ASSERT_NE(grid, std::string::npos);
  EXPECT_LT(html().find("id=\"fig-front\""), grid);
  EXPECT_LT(grid, html().find("id=\"fig-oblique-right\""));
  EXPECT_LT(html().find("id=\"fig-side-left\""), html().find("</div>", grid));
  EXPECT_GT(html().find("id=\"fig-distance\""), html().find("</div>", grid));
}

TEST(ReportHtml, NamesTheScanTemplateAndUnits) {
  const std::string& h = html();
  EXPECT_NE(h.find("cases/synth &lt;7&gt;/scan.ply"), std::string::npos);
  EXPECT_EQ(h.find("synth <7>"), std::string::npos);
  EXPECT_NE(h.find("default torso"), std::string::npos);
  EXPECT_NE(h.find("millimetres"), std::string::npos);
}

TEST(ReportHtml, ShowsEveryWarningEscapedInABoxAtTheTop) {
  const std::string& h = html();
  const size_t box = h.find("class=\"box warnings\"");
  ASSERT_NE(box, std::string::npos);
  EXPECT_LT(box, h.find("<h2>Summary"));
  for (const auto& w : test::report_test_result().warnings) EXPECT_NE(h.find(pipeline::html_escape(w)), std::string::npos) << w;
  EXPECT_NE(h.find("landmark &#39;nipple_L&#39; is 12.3 mm away from the scan surface"), std::string::npos);
  EXPECT_NE(h.find("a &lt;b&gt;bold&lt;/b&gt; &amp; &quot;quoted&quot; warning"), std::string::npos);
  EXPECT_EQ(h.find("<b>bold</b>"), std::string::npos);
  EXPECT_NE(h.find("Warnings (" + std::to_string(warned_result().warnings.size() + warned_result().breasts.warnings.size()) + ")"),
            std::string::npos);
}

TEST(ReportHtml, SaysSoWhenThereAreNoWarnings) {
  pipeline::RegisterResult r = test::report_test_result();
  r.warnings.clear();
  r.breasts.warnings.clear();
  const std::string h = pipeline::report_html(r, "t", figures());
  EXPECT_NE(h.find("No warnings."), std::string::npos);
  EXPECT_EQ(h.find("class=\"box warnings\""), std::string::npos);
}

TEST(ReportHtml, ContainsTheNumbersOfTheResult) {
  const auto& r = warned_result();
  const std::string& h = html();
  auto has = [&](const std::string& s) { return h.find(s) != std::string::npos; };
  EXPECT_TRUE(has(fixed(r.time_s, 2) + " s"));
  EXPECT_TRUE(has("<td>" + std::to_string(r.fit.summary.iterations.size())));
  EXPECT_TRUE(has(pipeline::html_escape(r.fit.summary.message)));
  // The paper's surface and landmark errors.
  EXPECT_TRUE(has("MAE <b>" + fixed(r.surface.mae, 2) + " mm</b>, SD " + fixed(r.surface.sd, 2) + " mm, max " +
                  fixed(r.surface.max, 1) + " mm"));
  EXPECT_TRUE(has(std::to_string(r.surface.n) + " of " + std::to_string(r.fitted_mm.V.rows())));
  // The template alone (before the surface detail), the number to judge the drawings by.
  ASSERT_TRUE(r.fit.summary.detail.applied);
  EXPECT_TRUE(has("Template alone"));
  EXPECT_TRUE(has("MAE <b>" + fixed(r.surface_model_only.mae, 2) + " mm</b>"));
  EXPECT_TRUE(has("by " + fixed(r.fit.summary.detail.mean_abs_mm, 1) + " mm on average"));
  const auto& l = r.landmarks.stats;
  ASSERT_GT(l.n, 0);
  EXPECT_TRUE(has("MAE <b>" + fixed(l.mae, 2) + " mm</b>, SD " + fixed(l.sd, 2) + " mm, max " + fixed(l.max, 1) +
                  " mm, min " + fixed(l.min, 1) + " mm"));
  for (size_t i = 0; i < r.landmarks.names.size(); ++i)
    EXPECT_TRUE(has("<td>" + r.landmarks.names[i] + "</td><td class=\"n\">" + fixed(r.landmarks.distances_mm[i], 1) + "</td>"))
        << r.landmarks.names[i];
  // Each landmark's check tolerance beside its error (30 mm for the mid-axillary line landmarks).
  ASSERT_FALSE(r.fit.summary.landmark_checks.empty());
  for (const auto& c : r.fit.summary.landmark_checks) {
    const size_t at = h.find("<td>" + c.name + "</td>");
    ASSERT_NE(at, std::string::npos) << c.name;
    EXPECT_NE(h.substr(at, h.find("</tr>", at) - at).find("<td class=\"n\">" + fixed(c.tolerance_mm, 0) + "</td>"),
              std::string::npos)
        << c.name;
  }
  // Each curve with its numbers and confidence.
  ASSERT_FALSE(r.drawings_on_scan.empty());
  for (const auto& c : r.drawings_on_scan) {
    const size_t at = h.find("<td>" + c.name);
    ASSERT_NE(at, std::string::npos) << c.name;
    const std::string line = h.substr(at, h.find("</tr>", at) - at);
    EXPECT_NE(line.find(fixed(c.length_mm, 1)), std::string::npos) << line;
    EXPECT_NE(line.find(fixed(100 * c.supported_fraction, 0) + " %"), std::string::npos) << line;
    EXPECT_NE(line.find(fixed(c.mean_model_to_scan_mm, 1)), std::string::npos) << line;
    EXPECT_NE(line.find(std::string(pipeline::confidence_name(pipeline::curve_confidence(c)))), std::string::npos) << line;
  }
  EXPECT_TRUE(has(pipeline::html_escape(pipeline::curve_confidence_rule())));
  // Breast measurements, with the note that volumes are relative.
  const auto& b = r.breasts;
  ASSERT_TRUE(b.right.volume_ml && b.left.volume_ml && b.inter_nipple_mm && b.volume_ratio);
  EXPECT_TRUE(has(fixed(*b.right.volume_ml, 0)));
  EXPECT_TRUE(has(fixed(*b.left.volume_ml, 0)));
  EXPECT_TRUE(has(fixed(*b.volume_ratio, 2)));
  EXPECT_TRUE(has(fixed(*b.right.notch_to_nipple_mm, 1)));
  EXPECT_TRUE(has(fixed(*b.left.nipple_to_imf_mm, 1)));
  EXPECT_TRUE(has(fixed(*b.inter_nipple_mm, 1)));
  EXPECT_TRUE(has("Volumes are relative"));
  // How to read it, and the other files.
  EXPECT_TRUE(has("How to read this report"));
  for (const auto& name : pipeline::register_output_names())
    if (name != "drawings.ply" && name != "drawings.obj") EXPECT_TRUE(has("<code>" + name + "</code>")) << name;
  EXPECT_TRUE(has("drawings.ply, drawings.obj"));
}

TEST(ReportHtml, ShowsTheProvenanceReadably) {
  pipeline::RegisterResult r = test::report_test_result();
  EXPECT_NE(pipeline::report_html(r, "t", figures()).find("Not recorded for this registration"), std::string::npos);
  pipeline::Provenance p;
  p.version = "0.1.0 (git abc1234)";
  p.inputs = {{"scan", "cases/a <b>/scan.ply", std::string(64, 'a')},
              {"landmarks", "cases/a/landmarks.mrk.json", std::string(64, 'b')},
              {"template", "/share/default_torso.glb", std::string(64, 'c')}};
  p.options.weights.set_lambda("landmarks", 12.5);
  p.started_utc = "2026-11-24T06:10:58Z";
  p.command_line = "breastfit register 'cases/a <b>/scan.ply' -o out";
  r.provenance = p;
  const std::string h = pipeline::report_html(r, "t", figures());
  auto has = [&](const std::string& s) { return h.find(s) != std::string::npos; };
  EXPECT_TRUE(has("<h2 id=\"provenance\">Traceability</h2>"));
  EXPECT_TRUE(has("<th>breastfit</th><td>0.1.0 (git abc1234)</td>"));
  EXPECT_TRUE(has("<th>scan</th><td><code>cases/a &lt;b&gt;/scan.ply</code>"));
  for (char c : {'a', 'b', 'c'}) EXPECT_TRUE(has("<code class=\"hash\">" + std::string(64, c) + "</code>")) << c;
  EXPECT_TRUE(has("<th>template</th><td><code>/share/default_torso.glb</code>"));
  // The run rows in their own tbody (the part that differs from run to run).
  const size_t run = h.find("<tbody class=\"run\">");
  ASSERT_NE(run, std::string::npos);
  const std::string run_rows = h.substr(run, h.find("</tbody>", run) - run);
  EXPECT_NE(run_rows.find("2026-11-24T06:10:58Z"), std::string::npos);
  EXPECT_NE(run_rows.find("breastfit register &#39;cases/a &lt;b&gt;/scan.ply&#39; -o out"), std::string::npos);
  // The effective options, collapsed (details), as the --config JSON.
  const size_t details = h.find("<details>");
  ASSERT_NE(details, std::string::npos);
  EXPECT_GT(details, h.find("id=\"provenance\""));
  const std::string opts = h.substr(details, h.find("</details>", details) - details);
  EXPECT_NE(opts.find("&quot;lambda_landmarks&quot;: 12.5"), std::string::npos) << opts.substr(0, 400);
  EXPECT_NE(opts.find("&quot;weights&quot;"), std::string::npos);
}

TEST(ReportHtml, SaysConvergedWhenTheSolverConvergedAndTheCapAsADetail) {
  pipeline::RegisterResult r = test::report_test_result();
  auto solver_row = [&](const pipeline::RegisterResult& res) {
    const std::string h = pipeline::report_html(res, "t", figures());
    const size_t at = h.find("<th>Solver</th>");
    EXPECT_NE(at, std::string::npos);
    return h.substr(at, h.find("</tr>", at) - at);
  };
  r.fit.summary.termination = fit::Termination::FunctionTolerance;
  std::string row = solver_row(r);
  EXPECT_NE(row.find("<b>converged</b> (function_tolerance)"), std::string::npos) << row;
  r.fit.summary.termination = fit::Termination::IterationCap;
  ASSERT_FALSE(r.fit.summary.iterations.empty());
  r.fit.summary.iterations.back().energy_before = 10.0;
  r.fit.summary.iterations.back().energy_after = 9.99;
  row = solver_row(r);
  EXPECT_EQ(row.find("converged</b>"), std::string::npos) << row;
  EXPECT_NE(row.find("<b>finished its iteration schedule</b> (its last step changed the energy by -0.10 %)"),
            std::string::npos)
      << row;
  // The stages with how each ended, as a detail.
  for (const auto& st : r.fit.summary.stages)
    EXPECT_NE(row.find(st.name + " " + std::to_string(st.iterations) + " ("), std::string::npos) << st.name << row;
}

TEST(ReportHtml, IsDeterministic) {
  EXPECT_EQ(pipeline::report_html(warned_result(), "default torso", figures()), html());
  // Rendering the figures again gives the same document.
  EXPECT_EQ(pipeline::report_html(warned_result(), "default torso",
                                  pipeline::render_report_figures(warned_result(), small_options())),
            html());
}

TEST(ReportHtml, WriteRendersAtTheDefaultSizeAndRegisterOutputsIncludeIt) {
  const fs::path dir = test::temp_dir();
  pipeline::write_register_outputs(dir, test::report_test_result(), test::report_test_model(), false, {});
  ASSERT_TRUE(fs::exists(dir / "report.html"));
  std::ifstream f(dir / "report.html", std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string h = ss.str();
  EXPECT_EQ(attribute_values(h, "src").size(), 6u);
  const auto widths = attribute_values(h, "width");
  ASSERT_EQ(widths.size(), 6u);
  for (size_t i = 0; i < widths.size(); ++i) EXPECT_EQ(widths[i], width_of(i, 900, 450)) << i;
  EXPECT_NE(h.find(test::report_test_model().name), std::string::npos);
  // Without the report: an old one is removed (it would describe another run).
  pipeline::RegisterOutputOptions no_html;
  no_html.report_html = false;
  pipeline::write_register_outputs(dir, test::report_test_result(), test::report_test_model(), true, {}, no_html);
  EXPECT_FALSE(fs::exists(dir / "report.html"));
  EXPECT_TRUE(fs::exists(dir / "report.json"));
}

}  // namespace
}  // namespace breastfit
