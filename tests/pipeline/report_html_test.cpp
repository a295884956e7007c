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

const pipeline::ReportFigures& figures() {
  static const pipeline::ReportFigures f = [] {
    ReportFigureOptions o;
    o.size = 320;
    return pipeline::render_report_figures(test::report_test_result(), o);
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
  EXPECT_EQ(srcs.size(), 3u);
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
    EXPECT_EQ(img.width(), 320);
    EXPECT_EQ(img.height(), 320);
    EXPECT_EQ(img.bytes(), figures().figures[i].image.bytes()) << i;
  }
  for (const auto& w : attribute_values(html(), "width")) EXPECT_EQ(w, "320");
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

TEST(ReportHtml, IsDeterministic) {
  EXPECT_EQ(pipeline::report_html(warned_result(), "default torso", figures()), html());
  // Rendering the figures again gives the same document.
  ReportFigureOptions o;
  o.size = 320;
  EXPECT_EQ(pipeline::report_html(warned_result(), "default torso", pipeline::render_report_figures(warned_result(), o)),
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
  EXPECT_EQ(attribute_values(h, "src").size(), 3u);
  for (const auto& w : attribute_values(h, "width")) EXPECT_EQ(w, "900");
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
