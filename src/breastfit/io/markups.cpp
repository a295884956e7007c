#include "breastfit/io/markups.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

#include "breastfit/core/errors.h"
#include "breastfit/io/detail/file_bytes.h"
#include "breastfit/io/detail/json_text.h"
#include "breastfit/io/detail/text.h"

namespace breastfit::io {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;

std::string read_text(const std::filesystem::path& path) { return detail::read_file_bytes(path, "markups file"); }


json parse_json(std::string_view text, const std::string& source) {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) throw IoError(source, "empty file");
  try {
    return json::parse(detail::quote_non_finite_tokens(text));
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    // "[json.exception.parse_error.101] parse error at line 3, column 5: ..." -> drop the prefix
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    throw IoError(source, "malformed JSON: " + what);
  }
}

enum class VecStatus { Ok, NonFinite, BadShape };

/// A JSON [x, y, z]; quoted "NaN"/"Infinity"/"-Infinity" count as non-finite numbers.
VecStatus read_vec3(const json& v, Vec3& out) {
  if (!v.is_array() || v.size() != 3) return VecStatus::BadShape;
  bool finite = true;
  for (int i = 0; i < 3; ++i) {
    const json& x = v[static_cast<size_t>(i)];
    if (x.is_number()) {
      out[i] = x.get<double>();
      if (!std::isfinite(out[i])) finite = false;
    } else if (x.is_string() && (x == "NaN" || x == "Infinity" || x == "-Infinity")) {
      out[i] = std::numeric_limits<double>::quiet_NaN();
      finite = false;
    } else {
      return VecStatus::BadShape;
    }
  }
  return finite ? VecStatus::Ok : VecStatus::NonFinite;
}

/// "mm" or "m" from a coordinateUnits value (string or coded array); absent = "mm".
std::string units_of(const json& markup, const std::string& source, const std::string& what) {
  auto it = markup.find("coordinateUnits");
  if (it == markup.end() || it->is_null()) return "mm";
  std::string code;
  if (it->is_string()) {
    code = it->get<std::string>();
  } else if (it->is_array() && !it->empty() && (*it)[0].is_string()) {
    code = (*it)[0].get<std::string>();
  } else {
    throw IoError(source, what + ": coordinateUnits must be a string or an array like [\"m\", \"UCUM\", \"meter\"]");
  }
  if (code == "mm" || code == "m") return code;
  throw IoError(source, what + ": unsupported coordinateUnits '" + code + "' (expected mm or m)");
}

bool is_ras(const json& markup, const std::string& source, const std::string& what) {
  auto it = markup.find("coordinateSystem");
  if (it == markup.end() || it->is_null()) return false;
  if (!it->is_string()) throw IoError(source, what + ": coordinateSystem must be \"LPS\" or \"RAS\"");
  const std::string cs = it->get<std::string>();
  if (cs == "LPS") return false;
  if (cs == "RAS") return true;
  throw IoError(source, what + ": unsupported coordinateSystem '" + cs + "' (expected LPS or RAS)");
}

/// Slicer's positionStatus of a control point that has no position: skipped while placing
/// ("missing"), never placed ("undefined") or still being placed ("preview").
bool is_unplaced(const json& status) {
  return status == "missing" || status == "undefined" || status == "preview";
}

}  // namespace

MarkupsFile parse_markups(std::string_view text, const std::string& source,
                          const MarkupsReadOptions& options) {
  const json doc = parse_json(text, source);
  if (!doc.is_object() || !doc.contains("markups") || !doc["markups"].is_array())
    throw IoError(source, "not a 3D Slicer markups file (no \"markups\" array)");

  MarkupsFile out;
  std::optional<std::string> common_units;
  const json& list = doc["markups"];
  for (size_t m = 0; m < list.size(); ++m) {
    const json& mk = list[m];
    if (!mk.is_object()) throw IoError(source, "markup #" + std::to_string(m + 1) + " is not an object");
    const std::string type = mk.contains("type") && mk["type"].is_string() ? mk["type"].get<std::string>() : "";
    const std::string name = mk.contains("name") && mk["name"].is_string() ? mk["name"].get<std::string>() : "";
    std::string what = "markup ";
    if (name.empty()) {
      what += '#';
      what += std::to_string(m + 1);
    } else {
      what += '\'';
      what += name;
      what += '\'';
    }
    const bool is_points = type == "Fiducial";
    const bool is_curve = type == "Curve" || type == "ClosedCurve" || type == "Line";
    if (!is_points && !is_curve) {
      if (type.empty()) throw IoError(source, what + " has no \"type\"");
      out.warnings.push_back(what + " of type " + type + " skipped (breastfit reads Fiducial, Curve, ClosedCurve and Line)");
      continue;
    }
    const bool ras = is_ras(mk, source, what);
    const std::string units = units_of(mk, source, what);
    if (!options.convert_to_mm) {
      if (common_units && *common_units != units)
        throw IoError(source, "markups declare different coordinateUnits (" + *common_units +
                                  " and " + units + ")");
      common_units = units;
    }
    const double scale = options.convert_to_mm && units == "m" ? 1000.0 : 1.0;

    std::vector<NamedPoint> pts;
    if (mk.contains("controlPoints") && !mk["controlPoints"].is_null()) {
      const json& cps = mk["controlPoints"];
      if (!cps.is_array()) throw IoError(source, what + ": \"controlPoints\" is not an array");
      for (size_t i = 0; i < cps.size(); ++i) {
        const json& cp = cps[i];
        if (!cp.is_object())
          throw IoError(source, what + ": control point #" + std::to_string(i + 1) + " is not an object");
        const std::string label = cp.contains("label") && cp["label"].is_string() ? cp["label"].get<std::string>() : "";
        std::string pwhat = what + " control point ";
        if (label.empty()) {
          pwhat += '#';
          pwhat += std::to_string(i + 1);
        } else {
          pwhat += '\'';
          pwhat += label;
          pwhat += '\'';
        }
        if (const auto status = cp.find("positionStatus"); status != cp.end() && is_unplaced(*status)) {
          out.warnings.push_back(pwhat + " skipped (positionStatus \"" + status->get<std::string>() +
                                 "\": not placed in Slicer)");
          continue;
        }
        if (!cp.contains("position")) throw IoError(source, pwhat + " has no position");
        Vec3 p;
        switch (read_vec3(cp["position"], p)) {
          case VecStatus::BadShape:
            throw IoError(source, pwhat + ": position is not an array of 3 numbers");
          case VecStatus::NonFinite:
            throw IoError(source, pwhat + " has a non-finite coordinate (NaN or Inf)");
          case VecStatus::Ok:
            break;
        }
        if (ras) {
          p.x() = -p.x();
          p.y() = -p.y();
        }
        pts.push_back({label, p * scale});
      }
    }
    if (is_points) {
      for (auto& p : pts) out.markups.points.push_back(std::move(p));
    } else {
      Curve c;
      c.name = name;
      c.closed = type == "ClosedCurve";
      c.points.resize(static_cast<Eigen::Index>(pts.size()), 3);
      for (size_t i = 0; i < pts.size(); ++i) c.points.row(static_cast<Eigen::Index>(i)) = pts[i].position.transpose();
      out.markups.curves.push_back(std::move(c));
    }
  }
  out.units = options.convert_to_mm ? "mm" : common_units.value_or("mm");
  return out;
}

MarkupsFile read_markups_file(const std::filesystem::path& path, const MarkupsReadOptions& options) {
  return parse_markups(read_text(path), path.string(), options);
}

Markups read_markups(const std::filesystem::path& path) {
  return read_markups_file(path, {}).markups;
}

void MarkupsWriteOptions::validate() const {
  if (units != "mm" && units != "m")
    throw InvalidInput("MarkupsWriteOptions.units = '" + units + "' is not one of mm, m");
  if (coordinate_system != "LPS" && coordinate_system != "RAS")
    throw InvalidInput("MarkupsWriteOptions.coordinate_system = '" + coordinate_system +
                       "' is not one of LPS, RAS");
  if (points_name.empty()) throw InvalidInput("MarkupsWriteOptions.points_name must not be empty");
  if (points_color)
    for (double c : *points_color)
      if (!(c >= 0 && c <= 1)) throw InvalidInput("MarkupsWriteOptions.points_color must be RGB values in [0, 1]");
}

namespace {

// The document as nlohmann's dump(1) printed the DOM the previous writer built (the same bytes:
// markups_test re-dumps the text and compares), written directly: a drawing's curves have
// hundreds of control points, and building each as a JSON object of ten keys cost more than
// printing it. Each level of the document is indented by one more space.
class MarkupsText {
 public:
  MarkupsText(const MarkupsWriteOptions& options, double scale) : options_(options), scale_(scale) {
    const bool ras = options.coordinate_system == "RAS";
    const double lps[9] = {-1.0, -0.0, -0.0, -0.0, -1.0, -0.0, 0.0, 0.0, 1.0};
    const double ras_values[9] = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    number_array(orientation_, ras ? ras_values : lps, 9, 5);
    detail::append_json_string(coordinate_system_, options.coordinate_system);
  }

  std::string& text() { return out_; }

  // One markup (level 2 of the document) with `count` control points: `point(i)` gives the i-th
  // point's position (LPS, input units), `label(out, i)` appends its quoted label and `what(i)`
  // names it in the error for a non-finite position.
  template <class Position, class Label, class What>
  void markup(std::string_view type, std::string_view name, std::size_t count, const Position& point,
              const Label& label, const What& what) {
    out_ += "  {\n   \"type\": ";
    detail::append_json_string(out_, type);
    out_ += ",\n   \"name\": ";
    detail::append_json_string(out_, name);
    out_ += ",\n   \"coordinateSystem\": " + coordinate_system_ + ",\n   \"coordinateUnits\": ";
    out_ += options_.units == "m" ? "[\n    \"m\",\n    \"UCUM\",\n    \"meter\"\n   ]" : "\"mm\"";
    out_ +=
        ",\n   \"locked\": false,\n   \"fixedNumberOfControlPoints\": false,\n   \"labelFormat\": \"%N-%d\",\n"
        "   \"lastUsedControlPointNumber\": ";
    detail::append_json_number(out_, count);
    out_ += ",\n   \"controlPoints\": ";
    if (count == 0) out_ += "[]";
    for (std::size_t i = 0; i < count; ++i) {
      out_ += i == 0 ? "[\n" : ",\n";
      control_point(i, point(i), label, what);
    }
    if (count > 0) out_ += "\n   ]";
    out_ += ",\n   \"measurements\": []";
  }

  void color_block(const std::array<double, 3>& rgb) {
    out_ += ",\n   \"display\": {\n    \"color\": ";
    color(rgb);
    out_ += ",\n    \"selectedColor\": ";
    color(rgb);
    out_ += "\n   }";
  }

 private:
  template <class Label, class What>
  void control_point(std::size_t i, const Vec3& p_lps, const Label& label, const What& what) {
    if (!p_lps.allFinite()) throw InvalidInput(what(i) + " has a non-finite coordinate (NaN or Inf)");
    Vec3 p = p_lps * scale_;
    if (options_.coordinate_system == "RAS") {
      p.x() = -p.x();
      p.y() = -p.y();
    }
    out_ += "    {\n     \"id\": \"";
    detail::append_json_number(out_, i + 1);
    out_ += "\",\n     \"label\": ";
    label(out_, i);
    out_ += ",\n     \"description\": \"\",\n     \"associatedNodeID\": \"\",\n     \"position\": [\n      ";
    detail::append_json_number(out_, p.x());
    out_ += ",\n      ";
    detail::append_json_number(out_, p.y());
    out_ += ",\n      ";
    detail::append_json_number(out_, p.z());
    out_ += "\n     ],\n     \"orientation\": ";
    out_ += orientation_;
    out_ +=
        ",\n     \"selected\": true,\n     \"locked\": false,\n     \"visibility\": true,\n"
        "     \"positionStatus\": \"defined\"\n    }";
  }
  void color(const std::array<double, 3>& rgb) { number_array(out_, rgb.data(), 3, 4); }
  // A non-empty array of numbers as dump(1) prints it at a member indented by `indent` spaces:
  // one number a line, one space deeper, then the closing bracket at the member's indentation.
  static void number_array(std::string& out, const double* values, int count, int indent) {
    out += "[\n";
    for (int i = 0; i < count; ++i) {
      out.append(static_cast<std::size_t>(indent + 1), ' ');
      detail::append_json_number(out, values[i]);
      out += i + 1 < count ? ",\n" : "\n";
    }
    out.append(static_cast<std::size_t>(indent), ' ');
    out += ']';
  }

  const MarkupsWriteOptions& options_;
  double scale_;
  std::string orientation_;        // the constant orientation array at its indentation
  std::string coordinate_system_;  // quoted
  std::string out_;
};

}  // namespace

std::string format_markups(const Markups& markups, const MarkupsWriteOptions& options,
                           std::string_view input_units) {
  options.validate();
  if (input_units != "mm" && input_units != "m")
    throw InvalidInput("format_markups: input units '" + std::string(input_units) + "' is not one of mm, m");
  const double in_to_mm = input_units == "m" ? 1000.0 : 1.0;
  const double mm_to_out = options.units == "m" ? 1e-3 : 1.0;
  MarkupsText doc(options, in_to_mm * mm_to_out);
  std::string& out = doc.text();
  std::size_t points = 0;
  for (const Curve& c : markups.curves) points += static_cast<std::size_t>(c.points.rows());
  out.reserve(1024 + 640 * (points + markups.points.size()));
  out +=
      "{\n \"@schema\": \"https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/"
      "Resources/Schema/markups-schema-v1.0.3.json#\",\n \"markups\": ";
  const std::size_t count = (markups.points.empty() ? 0 : 1) + markups.curves.size();
  if (count == 0) out += "[]";
  std::size_t written = 0;
  auto next_markup = [&] { out += written++ == 0 ? "[\n" : ",\n"; };
  if (!markups.points.empty()) {
    next_markup();
    doc.markup(
        "Fiducial", options.points_name, markups.points.size(), [&](std::size_t i) { return markups.points[i].position; },
        [&](std::string& o, std::size_t i) { detail::append_json_string(o, markups.points[i].name); },
        [&](std::size_t i) { return "point '" + markups.points[i].name + "'"; });
    if (options.points_color) doc.color_block(*options.points_color);
    out += "\n  }";
  }
  for (const Curve& c : markups.curves) {
    next_markup();
    std::string quoted;  // the curve's name quoted, without its closing quote: labels are name-i
    detail::append_json_string(quoted, c.name);
    quoted.pop_back();
    doc.markup(
        c.closed ? "ClosedCurve" : "Curve", c.name, static_cast<std::size_t>(c.points.rows()),
        [&](std::size_t i) { return Vec3(c.points.row(static_cast<Eigen::Index>(i)).transpose()); },
        [&](std::string& o, std::size_t i) {
          o += quoted;
          o += '-';
          detail::append_json_number(o, i + 1);
          o += '"';
        },
        [&](std::size_t i) { return "curve '" + c.name + "' point " + std::to_string(i + 1); });
    out += "\n  }";
  }
  if (count > 0) out += "\n ]";
  out += "\n}\n";
  return std::move(out);
}

void write_markups(const std::filesystem::path& path, const Markups& markups,
                   const MarkupsWriteOptions& options) {
  const std::string text = format_markups(markups, options);
  const std::string name = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError(name, "is a directory, cannot write markups there");
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw IoError(name, "cannot open for writing");
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.flush();
  if (!out) throw IoError(name, "write failed");
}

}  // namespace breastfit::io
