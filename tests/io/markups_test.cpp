#include "breastfit/io/markups.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "breastfit/core/errors.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

namespace fs = std::filesystem;

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

Markups sample() {
  Markups m;
  m.points.push_back({"sternal_notch", Vec3(-163.482017, 248.322212, 102.238829)});
  m.points.push_back({"nipple_L", Vec3(0.1, -2.5e-3, 1e5 / 3.0)});
  Curve open;
  open.name = "sternum";
  open.points.resize(3, 3);
  open.points << 0, 0, 0, 1.5, -2, 3, 1.0 / 3.0, 2, 7;
  Curve closed;
  closed.name = "breast_contour_R";
  closed.closed = true;
  closed.points.resize(4, 3);
  closed.points << 10, 0, 0, 0, 10, 0, -10, 0, 0, 0, -10, 0;
  m.curves = {open, closed};
  return m;
}

/// The message of the IoError thrown by fn (fails when nothing or something else is thrown).
template <class Fn>
std::string io_error_of(Fn&& fn) {
  try {
    fn();
  } catch (const IoError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no IoError";
  return {};
}

std::string markup_json(const std::string& type, const std::string& name, const std::string& cs,
                        const std::string& units_json, const std::string& control_points) {
  return R"({"@schema": "x", "markups": [{"type": ")" + type + R"(", "name": ")" + name +
         R"(", "coordinateSystem": ")" + cs + R"(", "coordinateUnits": )" + units_json +
         R"(, "controlPoints": [)" + control_points + "]}]}";
}

TEST(Markups, RoundTripIsExactInMillimetresLps) {
  const fs::path p = test::temp_dir() / "out.mrk.json";
  const Markups m = sample();
  write_markups(p, m);
  const Markups r = read_markups(p);
  ASSERT_EQ(r.points.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(r.points[i].name, m.points[i].name);
    EXPECT_EQ(r.points[i].position, m.points[i].position);  // bit-identical
  }
  ASSERT_EQ(r.curves.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(r.curves[i].name, m.curves[i].name);
    EXPECT_EQ(r.curves[i].closed, m.curves[i].closed);
    EXPECT_EQ(r.curves[i].points, m.curves[i].points);
  }
}

TEST(Markups, WrittenFileIsSlicerShaped) {
  const fs::path p = test::temp_dir() / "out.mrk.json";
  write_markups(p, sample(), {.units = "mm", .coordinate_system = "LPS", .points_name = "lm"});
  std::ifstream in(p);
  const nlohmann::json doc = nlohmann::json::parse(in);
  EXPECT_NE(doc["@schema"].get<std::string>().find("markups-schema-v1.0.3"), std::string::npos);
  ASSERT_EQ(doc["markups"].size(), 3u);
  const auto& pts = doc["markups"][0];
  EXPECT_EQ(pts["type"], "Fiducial");
  EXPECT_EQ(pts["name"], "lm");
  EXPECT_EQ(pts["coordinateSystem"], "LPS");
  EXPECT_EQ(pts["coordinateUnits"], "mm");
  const auto& cp = pts["controlPoints"][1];
  EXPECT_EQ(cp["id"], "2");
  EXPECT_EQ(cp["label"], "nipple_L");
  EXPECT_EQ(cp["positionStatus"], "defined");
  EXPECT_EQ(cp["orientation"].size(), 9u);
  for (const char* key : {"selected", "locked", "visibility"}) EXPECT_TRUE(cp[key].is_boolean()) << key;
  EXPECT_EQ(doc["markups"][1]["type"], "Curve");
  EXPECT_EQ(doc["markups"][1]["name"], "sternum");
  EXPECT_EQ(doc["markups"][2]["type"], "ClosedCurve");
  EXPECT_EQ(doc["markups"][2]["controlPoints"].size(), 4u);
}

TEST(Markups, MetresAndRasWrittenAndReadBack) {
  const fs::path p = test::temp_dir() / "m_ras.mrk.json";
  const Markups m = sample();
  write_markups(p, m, {.units = "m", .coordinate_system = "RAS"});
  std::ifstream in(p);
  const nlohmann::json doc = nlohmann::json::parse(in);
  const auto& pts = doc["markups"][0];
  EXPECT_EQ(pts["coordinateSystem"], "RAS");
  EXPECT_EQ(pts["coordinateUnits"], nlohmann::json::parse(R"(["m", "UCUM", "meter"])"));
  // RAS metres: x and y negated, divided by 1000.
  EXPECT_NEAR(pts["controlPoints"][0]["position"][0].get<double>(), 0.163482017, 1e-15);
  EXPECT_NEAR(pts["controlPoints"][0]["position"][1].get<double>(), -0.248322212, 1e-15);
  EXPECT_NEAR(pts["controlPoints"][0]["position"][2].get<double>(), 0.102238829, 1e-15);
  const Markups r = read_markups(p);  // back to LPS mm
  ASSERT_EQ(r.points.size(), 2u);
  for (size_t i = 0; i < 2; ++i)
    EXPECT_LT((r.points[i].position - m.points[i].position).norm(), 1e-9);
  EXPECT_LT((r.curves[1].points - m.curves[1].points).norm(), 1e-9);
  const MarkupsFile raw = read_markups_file(p, {.convert_to_mm = false});
  EXPECT_EQ(raw.units, "m");
  EXPECT_NEAR(raw.markups.points[0].position.x(), -0.163482017, 1e-15);
}

TEST(Markups, ReadsRasAndUnitVariants) {
  const fs::path dir = test::temp_dir();
  const std::string cp = R"({"id": "1", "label": "xiphoid", "position": [1.0, 2.0, 3.0]})";
  struct Case {
    std::string cs, units;
    Vec3 expected;
  } cases[] = {{"LPS", R"("mm")", {1, 2, 3}},
               {"RAS", R"("mm")", {-1, -2, 3}},
               {"LPS", R"("m")", {1000, 2000, 3000}},
               {"RAS", R"(["m", "UCUM", "meter"])", {-1000, -2000, 3000}},
               {"LPS", R"(["mm", "UCUM", "millimeter"])", {1, 2, 3}}};
  for (const Case& c : cases) {
    const fs::path p = dir / "c.mrk.json";
    write_text(p, markup_json("Fiducial", "F", c.cs, c.units, cp));
    const Markups m = read_markups(p);
    ASSERT_EQ(m.points.size(), 1u);
    EXPECT_EQ(m.points[0].name, "xiphoid");
    EXPECT_EQ(m.points[0].position, c.expected) << c.cs << " " << c.units;
  }
  // Absent coordinateSystem / coordinateUnits: LPS mm.
  const fs::path p = dir / "bare.mrk.json";
  write_text(p, R"({"markups": [{"type": "Fiducial", "controlPoints": [)" + cp + "]}]}");
  EXPECT_EQ(read_markups(p).points[0].position, Vec3(1, 2, 3));
}

TEST(Markups, SeveralMarkupsLinesAndSkippedTypes) {
  const fs::path p = test::temp_dir() / "multi.mrk.json";
  write_text(p, R"({"markups": [
    {"type": "Fiducial", "name": "a", "controlPoints": [{"label": "p1", "position": [1, 1, 1]}]},
    {"type": "Line", "name": "ruler", "controlPoints": [
       {"label": "x", "position": [0, 0, 0]}, {"label": "y", "position": [3, 4, 0]}]},
    {"type": "Plane", "name": "midline", "controlPoints": [{"position": [0, 0, 0]}]},
    {"type": "ROI", "controlPoints": []},
    {"type": "Angle", "name": "tilt", "controlPoints": []},
    {"type": "ClosedCurve", "name": "loop", "coordinateSystem": "RAS", "controlPoints": [
       {"position": [1, 0, 0]}, {"position": [0, 1, 0]}, {"position": [0, 0, 1]}]},
    {"type": "Fiducial", "name": "b", "coordinateUnits": "m", "controlPoints": [
       {"label": "p2", "position": [0.001, 0.002, 0.003]}]}]})");
  const MarkupsFile f = read_markups_file(p, {});
  const Markups& m = f.markups;
  ASSERT_EQ(m.points.size(), 2u);
  EXPECT_EQ(m.points[0].name, "p1");
  EXPECT_EQ(m.points[1].name, "p2");
  EXPECT_LT((m.points[1].position - Vec3(1, 2, 3)).norm(), 1e-12);
  ASSERT_EQ(m.curves.size(), 2u);
  EXPECT_EQ(m.curves[0].name, "ruler");  // a Line is an open curve of its two points
  EXPECT_FALSE(m.curves[0].closed);
  EXPECT_EQ(m.curves[0].length(), 5.0);
  EXPECT_TRUE(m.curves[1].closed);
  EXPECT_EQ(m.curves[1].name, "loop");
  EXPECT_EQ(m.curves[1].points.row(0), Eigen::RowVector3d(-1, 0, 0));
  EXPECT_NEAR(m.curves[1].length(), 3 * std::sqrt(2.0), 1e-12);
  ASSERT_NE(m.find_curve("loop"), nullptr);
  EXPECT_EQ(m.find_point("p2")->name, "p2");
  EXPECT_EQ(m.find_point("ruler"), nullptr);
  // The skipped markups are named, with their type.
  ASSERT_EQ(f.warnings.size(), 3u);
  EXPECT_EQ(f.warnings[0], "markup 'midline' of type Plane skipped (breastfit reads Fiducial, Curve, ClosedCurve and Line)");
  EXPECT_NE(f.warnings[1].find("markup #4 of type ROI skipped"), std::string::npos) << f.warnings[1];
  EXPECT_NE(f.warnings[2].find("markup 'tilt' of type Angle skipped"), std::string::npos) << f.warnings[2];
  // Mixed units cannot be kept raw.
  EXPECT_NE(io_error_of([&] { read_markups_file(p, {.convert_to_mm = false}); }).find("different coordinateUnits"),
            std::string::npos);
}

TEST(Markups, UnplacedControlPointsAreSkippedWithAWarning) {
  const fs::path p = test::temp_dir() / "unplaced.mrk.json";
  write_text(p, R"({"markups": [{"type": "Fiducial", "name": "F", "controlPoints": [
       {"label": "nipple_R", "position": "", "positionStatus": "missing"},
       {"label": "xiphoid", "position": [1, 2, 3], "positionStatus": "defined"},
       {"label": "later", "positionStatus": "undefined"},
       {"position": [0, 0, 0], "positionStatus": "preview"}]}]})");
  const MarkupsFile f = read_markups_file(p, {});
  ASSERT_EQ(f.markups.points.size(), 1u);
  EXPECT_EQ(f.markups.points[0].name, "xiphoid");
  ASSERT_EQ(f.warnings.size(), 3u);
  EXPECT_EQ(f.warnings[0],
            "markup 'F' control point 'nipple_R' skipped (positionStatus \"missing\": not placed in Slicer)");
  EXPECT_NE(f.warnings[1].find("'later' skipped (positionStatus \"undefined\""), std::string::npos) << f.warnings[1];
  EXPECT_NE(f.warnings[2].find("control point #4 skipped (positionStatus \"preview\""), std::string::npos)
      << f.warnings[2];
  // Without a status saying so, an empty position is still an error.
  write_text(p, R"({"markups": [{"type": "Fiducial", "controlPoints": [{"label": "a", "position": ""}]}]})");
  EXPECT_NE(io_error_of([&] { read_markups(p); }).find("not an array of 3 numbers"), std::string::npos);
}

TEST(Markups, ReadsBenchmarkStyleFile) {
  const fs::path p = test::temp_dir() / "bench_like.mrk.json";
  write_text(p, R"({
 "@schema": "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/Resources/Schema/markups-schema-v1.0.3.json#",
 "markups": [{"type": "Fiducial", "name": "landmarks", "coordinateSystem": "LPS",
   "coordinateUnits": "mm", "locked": false, "fixedNumberOfControlPoints": false,
   "labelFormat": "%N-%d", "lastUsedControlPointNumber": 1,
   "controlPoints": [{"id": "1", "label": "sternal_notch", "description": "", "associatedNodeID": "",
     "position": [-163.482017, 248.322212, 102.238829],
     "orientation": [-1.0, -0.0, -0.0, -0.0, -1.0, -0.0, 0.0, 0.0, 1.0],
     "selected": true, "locked": false, "visibility": true, "positionStatus": "defined"}],
   "measurements": [], "display": {"visibility": true, "opacity": 1.0}}]})");
  const Markups m = read_markups(p);
  ASSERT_EQ(m.points.size(), 1u);
  EXPECT_EQ(m.points[0].position, Vec3(-163.482017, 248.322212, 102.238829));
}

TEST(Markups, Errors) {
  const fs::path dir = test::temp_dir();
  auto err = [&](const std::string& text) {
    const fs::path p = dir / "bad.mrk.json";
    write_text(p, text);
    const std::string msg = io_error_of([&] { read_markups(p); });
    EXPECT_NE(msg.find("bad.mrk.json"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "multi-line: " << msg;
    return msg;
  };
  EXPECT_NE(err("").find("empty file"), std::string::npos);
  EXPECT_NE(err("{\"markups\": [").find("malformed JSON"), std::string::npos);
  EXPECT_NE(err("[1, 2]").find("not a 3D Slicer markups file"), std::string::npos);
  EXPECT_NE(err(R"({"markups": [{"type": "Fiducial", "controlPoints": [{"label": "a"}]}]})").find("'a' has no position"),
            std::string::npos);
  EXPECT_NE(err(R"({"markups": [{"type": "Fiducial", "controlPoints": [{"label": "a", "position": [1, 2]}]}]})")
                .find("not an array of 3 numbers"),
            std::string::npos);
  EXPECT_NE(err(R"({"markups": [{"type": "Fiducial", "controlPoints": [{"label": "nanpt", "position": [NaN, 2, 3]}]}]})")
                .find("'nanpt' has a non-finite coordinate"),
            std::string::npos);
  EXPECT_NE(err(markup_json("Fiducial", "F", "XYZ", "\"mm\"", "")).find("unsupported coordinateSystem 'XYZ'"),
            std::string::npos);
  EXPECT_NE(err(markup_json("Fiducial", "F", "LPS", "\"cm\"", "")).find("unsupported coordinateUnits 'cm'"),
            std::string::npos);
  EXPECT_NE(err(R"({"markups": [{"name": "typeless"}]})").find("no \"type\""), std::string::npos);
  EXPECT_NE(io_error_of([&] { read_markups(dir / "missing.mrk.json"); }).find("does not exist"), std::string::npos);
  EXPECT_NE(io_error_of([&] { read_markups(dir); }).find("directory"), std::string::npos);
}

/// The document as the writer built it before it wrote text directly: a DOM of ordered_json
/// dumped with indent 1 (the reference the direct writer must match byte for byte).
std::string dom_markups(const Markups& markups, const MarkupsWriteOptions& options, double scale) {
  using nlohmann::ordered_json;
  const bool ras = options.coordinate_system == "RAS";
  const ordered_json orientation = ras ? ordered_json::array({1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0})
                                       : ordered_json::array({-1.0, -0.0, -0.0, -0.0, -1.0, -0.0, 0.0, 0.0, 1.0});
  auto control_point = [&](size_t i, const std::string& label, Vec3 p) {
    p *= scale;
    if (ras) p.head<2>() = -p.head<2>();
    ordered_json cp;
    cp["id"] = std::to_string(i + 1);
    cp["label"] = label;
    cp["description"] = "";
    cp["associatedNodeID"] = "";
    cp["position"] = ordered_json::array({p.x(), p.y(), p.z()});
    cp["orientation"] = orientation;
    cp["selected"] = true;
    cp["locked"] = false;
    cp["visibility"] = true;
    cp["positionStatus"] = "defined";
    return cp;
  };
  auto markup = [&](const std::string& type, const std::string& name, ordered_json cps) {
    ordered_json m;
    m["type"] = type;
    m["name"] = name;
    m["coordinateSystem"] = options.coordinate_system;
    m["coordinateUnits"] = options.units == "m" ? ordered_json::array({"m", "UCUM", "meter"}) : ordered_json("mm");
    m["locked"] = false;
    m["fixedNumberOfControlPoints"] = false;
    m["labelFormat"] = "%N-%d";
    m["lastUsedControlPointNumber"] = cps.size();
    m["controlPoints"] = std::move(cps);
    m["measurements"] = ordered_json::array();
    return m;
  };
  ordered_json doc;
  doc["@schema"] =
      "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/Resources/"
      "Schema/markups-schema-v1.0.3.json#";
  doc["markups"] = ordered_json::array();
  if (!markups.points.empty()) {
    ordered_json cps = ordered_json::array();
    for (size_t i = 0; i < markups.points.size(); ++i)
      cps.push_back(control_point(i, markups.points[i].name, markups.points[i].position));
    ordered_json points = markup("Fiducial", options.points_name, std::move(cps));
    if (options.points_color) {
      const ordered_json rgb = *options.points_color;
      points["display"] = {{"color", rgb}, {"selectedColor", rgb}};
    }
    doc["markups"].push_back(std::move(points));
  }
  for (const Curve& c : markups.curves) {
    ordered_json cps = ordered_json::array();
    for (Eigen::Index i = 0; i < c.points.rows(); ++i)
      cps.push_back(control_point(static_cast<size_t>(i), c.name + "-" + std::to_string(i + 1), c.points.row(i).transpose()));
    doc["markups"].push_back(markup(c.closed ? "ClosedCurve" : "Curve", c.name, std::move(cps)));
  }
  return doc.dump(1) + "\n";
}

TEST(Markups, TextIsTheSameBytesAsTheJsonLibrarysDump) {
  Markups m = sample();
  m.points.push_back({"odd \"name\"\t\xc3\xa9", Vec3(-0.0, 1e-7, -1.2345678901234567e21)});
  m.curves.push_back(Curve{"empty", false, Points(0, 3)});
  m.curves[0].points(1, 2) = 5e-324;  // the smallest subnormal
  for (const std::string cs : {"LPS", "RAS"})
    for (const std::string units : {"mm", "m"})
      for (const bool colour : {false, true}) {
        MarkupsWriteOptions o;
        o.coordinate_system = cs;
        o.units = units;
        if (colour) o.points_color = std::array<double, 3>{0.0, 0.75, 1.0 / 3.0};
        const double scale = units == "m" ? 1e-3 : 1.0;
        EXPECT_EQ(format_markups(m, o), dom_markups(m, o, scale)) << cs << " " << units << " " << colour;
        EXPECT_EQ(format_markups(m, o, "m"), dom_markups(m, o, 1000.0 * scale)) << cs << " " << units;
      }
  EXPECT_EQ(format_markups(Markups{}, {}), dom_markups(Markups{}, {}, 1.0));
  Markups points_only;
  points_only.points = m.points;
  EXPECT_EQ(format_markups(points_only, {}), dom_markups(points_only, {}, 1.0));
}

TEST(Markups, WriteValidatesOptionsAndValues) {
  const fs::path p = test::temp_dir() / "w.mrk.json";
  EXPECT_THROW(write_markups(p, sample(), {.units = "cm"}), InvalidInput);
  EXPECT_THROW(write_markups(p, sample(), {.coordinate_system = "RAI"}), InvalidInput);
  Markups bad = sample();
  bad.points[1].position.y() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(write_markups(p, bad), InvalidInput);
  EXPECT_THROW(write_markups(test::temp_dir(), sample()), IoError);
  // No points: curves only, no empty Fiducial.
  Markups curves_only = sample();
  curves_only.points.clear();
  write_markups(p, curves_only);
  std::ifstream in(p);
  EXPECT_EQ(nlohmann::json::parse(in)["markups"].size(), 2u);
}

TEST(Markups, PointsColourAndNameAreWrittenForSlicer) {
  Markups m;
  m.points.push_back({"nipple_R", Vec3(1, 2, 3)});
  MarkupsWriteOptions o;
  o.points_name = "fitted";
  o.points_color = std::array<double, 3>{0.0, 0.75, 1.0};
  const auto doc = nlohmann::json::parse(format_markups(m, o));
  EXPECT_EQ(doc["markups"][0]["name"], "fitted");
  EXPECT_EQ(doc["markups"][0]["display"]["selectedColor"], nlohmann::json::array({0.0, 0.75, 1.0}));
  EXPECT_EQ(doc["markups"][0]["display"]["color"], nlohmann::json::array({0.0, 0.75, 1.0}));
  EXPECT_FALSE(nlohmann::json::parse(format_markups(m, {}))["markups"][0].contains("display"));
  o.points_color = std::array<double, 3>{0.0, 2.0, 1.0};
  EXPECT_THROW(format_markups(m, o), InvalidInput);
}

}  // namespace
}  // namespace breastfit::io
