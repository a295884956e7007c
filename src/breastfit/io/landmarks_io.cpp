#include "breastfit/io/landmarks_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/io/detail/file_bytes.h"
#include "breastfit/io/detail/text.h"
#include "breastfit/io/markups.h"
#include "breastfit/mesh/landmark_names.h"

namespace breastfit::io {
namespace {

using nlohmann::ordered_json;

std::string read_text(const std::filesystem::path& path) { return detail::read_file_bytes(path, "landmark file"); }

bool is_blank_text(std::string_view s) {
  return s.find_first_not_of(" \t\r\n\f\v") == std::string_view::npos;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool ends_with(const std::string& s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}


/// {name: [x, y, z]} in file order; duplicate keys are kept (validated later).
std::vector<NamedPoint> parse_plain_json(const ordered_json& doc, const std::vector<std::string>& keys,
                                         const std::string& source) {
  if (!doc.is_object())
    throw IoError(source, "expected a JSON object {\"name\": [x, y, z], ...}");
  std::vector<NamedPoint> pts;
  for (const std::string& key : keys) {
    const ordered_json& v = doc.at(key);
    if (!v.is_array() || v.size() != 3)
      throw IoError(source, "landmark '" + key + "': expected [x, y, z], got " + v.dump().substr(0, 60));
    Vec3 p;
    for (int i = 0; i < 3; ++i) {
      const ordered_json& x = v[static_cast<size_t>(i)];
      if (x.is_number()) {
        p[i] = x.get<double>();
      } else if (x.is_string() && (x == "NaN" || x == "Infinity" || x == "-Infinity")) {
        p[i] = std::numeric_limits<double>::quiet_NaN();
      } else {
        throw IoError(source, "landmark '" + key + "': expected [x, y, z] numbers, got " + v.dump().substr(0, 60));
      }
    }
    pts.push_back({key, p});
  }
  return pts;
}

/// The fields of a comma-separated line, each trimmed.
std::vector<std::string_view> split_commas(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

/// The next line of `text` (removed from it, without its '\n').
std::string_view next_line(std::string_view& text) {
  const size_t eol = text.find('\n');
  const std::string_view line = text.substr(0, eol);
  text.remove_prefix(eol == std::string_view::npos ? text.size() : eol + 1);
  return line;
}

/// The value of a "# key = value" header line of a .fcsv file (`line` after its '#'), or
/// nullopt when the line sets another key.
std::optional<std::string_view> fcsv_header(std::string_view line, std::string_view key) {
  line = trim(line);
  if (line.substr(0, key.size()) != key) return std::nullopt;
  line = trim(line.substr(key.size()));
  if (line.empty() || line.front() != '=') return std::nullopt;
  return trim(line.substr(1));
}

/// The fields of one CSV row as 3D Slicer writes .fcsv rows: a field in double quotes may hold
/// commas, and "" inside it is one quote ("label, left","the ""upper"" point").
std::vector<std::string> split_csv_row(std::string_view line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"' && trim(fields.back()).empty()) {
      fields.back().clear();
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  for (std::string& f : fields) f = std::string(trim(f));
  return fields;
}

/// A legacy 3D Slicer fiducial list (.fcsv): '#' header lines, then one row per point. The
/// columns header names the x, y, z and label columns (Slicer's order when absent); the
/// CoordinateSystem header "RAS" or "0" (the default) is converted to LPS by negating x and y
/// (as the markups reader does), "LPS" or "1" is kept.
std::vector<NamedPoint> parse_fcsv(std::string_view text, const std::string& source) {
  std::vector<std::string_view> columns = split_commas("id,x,y,z,ow,ox,oy,oz,vis,sel,lock,label,desc,associatedNodeID");
  bool ras = true;
  std::vector<NamedPoint> pts;
  size_t line_no = 0;
  while (!text.empty()) {
    std::string_view line = trim(next_line(text));
    ++line_no;
    const std::string where = "line " + std::to_string(line_no) + ": ";
    if (line.empty()) continue;
    if (line.front() == '#') {
      if (const auto cs = fcsv_header(line.substr(1), "CoordinateSystem")) {
        if (*cs == "RAS" || *cs == "0") {
          ras = true;
        } else if (*cs == "LPS" || *cs == "1") {
          ras = false;
        } else {
          throw IoError(source, where + "unsupported CoordinateSystem '" + std::string(*cs) +
                                    "' (expected RAS, LPS, 0 or 1)");
        }
      } else if (const auto cols = fcsv_header(line.substr(1), "columns")) {
        columns = split_commas(*cols);
      }
      continue;
    }
    const std::vector<std::string> fields = split_csv_row(line);
    double xyz[3];
    const char* axes[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
      const auto col = std::find(columns.begin(), columns.end(), axes[a]);
      if (col == columns.end()) throw IoError(source, where + "the columns header has no '" + axes[a] + "' column");
      const auto i = static_cast<size_t>(col - columns.begin());
      if (i >= fields.size() || !detail::parse_double(fields[i], xyz[a]))
        throw IoError(source, where + "expected a number in column '" + axes[a] + "'");
    }
    const auto label = std::find(columns.begin(), columns.end(), "label");
    const auto li = static_cast<size_t>(label - columns.begin());
    if (label == columns.end() || li >= fields.size() || fields[li].empty())
      throw IoError(source, where + "the point has no label");
    const double sign = ras ? -1.0 : 1.0;
    pts.push_back({std::string(fields[li]), Vec3(sign * xyz[0], sign * xyz[1], xyz[2])});
  }
  return pts;
}

std::vector<NamedPoint> parse_csv(std::string_view text, const std::string& source) {
  std::vector<NamedPoint> pts;
  size_t line_no = 0;
  bool seen_content = false;
  while (!text.empty()) {
    std::string_view line = next_line(text);
    ++line_no;
    if (line_no == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // UTF-8 BOM
    line = trim(line);
    if (line.empty() || line.front() == '#') continue;

    std::vector<std::string_view> fields;
    if (line.find(',') != std::string_view::npos) {
      fields = split_commas(line);
      if (fields.size() == 5 && fields.back().empty()) fields.pop_back();  // trailing comma
    } else {
      std::string_view rest = line;
      for (std::string_view tok = detail::next_token(rest); !tok.empty(); tok = detail::next_token(rest))
        fields.push_back(tok);
    }
    const bool first = !seen_content;
    seen_content = true;
    double xyz[3];
    bool numeric = fields.size() == 4;
    for (size_t i = 1; numeric && i < 4; ++i) numeric = detail::parse_double(fields[i], xyz[i - 1]);
    if (!numeric) {
      if (first && fields.size() == 4) {  // a header such as "name,x,y,z": no numeric field
        double tmp;
        bool any_number = false;
        for (size_t i = 1; i < 4; ++i) any_number = any_number || detail::parse_double(fields[i], tmp);
        if (!any_number) continue;
      }
      const std::string where = "line " + std::to_string(line_no) + ": ";
      if (fields.size() != 4)
        throw IoError(source, where + "expected 'name,x,y,z', got " + std::to_string(fields.size()) + " fields");
      for (size_t i = 1; i < 4; ++i) {
        double tmp;
        if (!detail::parse_double(fields[i], tmp))
          throw IoError(source, where + "'" + std::string(fields[i].substr(0, 32)) + "' is not a number");
      }
    }
    std::string name(fields[0]);
    if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
    if (name.empty()) throw IoError(source, "line " + std::to_string(line_no) + ": empty landmark name");
    pts.push_back({name, Vec3(xyz[0], xyz[1], xyz[2])});
  }
  return pts;
}

void validate(const std::vector<NamedPoint>& pts, const std::string& source,
              const LandmarkReadOptions& options) {
  if (pts.empty()) throw IoError(source, "contains no landmarks");
  std::set<std::string> seen;
  for (const NamedPoint& p : pts) {
    if (options.require_known_names && !landmark_index(p.name))
      throw IoError(source, "unknown landmark '" + p.name + "' (expected one of: " + landmark_name_list() + ")");
    if (!seen.insert(p.name).second) throw IoError(source, "landmark '" + p.name + "' appears more than once");
    if (!p.position.allFinite())
      throw IoError(source, "landmark '" + p.name + "' has a non-finite coordinate (NaN or Inf)");
  }
}

}  // namespace

LandmarkSet read_landmarks(const std::filesystem::path& path, const LandmarkReadOptions& options) {
  const std::string source = path.string();
  const std::string name = lower(path.filename().string());
  const bool is_json = ends_with(name, ".json");
  const bool is_csv = ends_with(name, ".csv");
  const bool is_fcsv = ends_with(name, ".fcsv");
  if (!is_json && !is_csv && !is_fcsv)
    throw IoError(source, "unsupported landmark file extension '" + path.extension().string() +
                              "' (supported landmark files: " + std::string(kLandmarkExtensions) + ")");
  const std::string text = read_text(path);
  if (is_blank_text(text)) throw IoError(source, "empty file");

  LandmarkSet out;
  if (is_csv) {
    out.points = parse_csv(text, source);
  } else if (is_fcsv) {
    out.points = parse_fcsv(text, source);
    out.declared_units = "mm";  // Slicer's fiducial lists are always in millimetres
  } else {
    // Parse once, recording top-level keys in order (to catch duplicates nlohmann would merge).
    std::vector<std::string> keys;
    ordered_json doc;
    try {
      doc = ordered_json::parse(detail::quote_non_finite_tokens(text),
                                [&](int depth, ordered_json::parse_event_t event, ordered_json& parsed) {
                                  if (depth == 1 && event == ordered_json::parse_event_t::key)
                                    keys.push_back(parsed.get<std::string>());
                                  return true;
                                });
    } catch (const ordered_json::parse_error& e) {
      std::string what = e.what();
      const auto pos = what.find("] ");
      if (pos != std::string::npos) what = what.substr(pos + 2);
      throw IoError(source, "malformed JSON: " + what);
    }
    if (ends_with(name, ".mrk.json") || (doc.is_object() && doc.contains("markups"))) {
      const MarkupsFile mf = parse_markups(text, source, {.convert_to_mm = false});
      out.points = mf.markups.points;
      out.declared_units = mf.units;
      out.warnings = mf.warnings;
    } else {
      std::vector<std::string> unique_keys;
      std::set<std::string> seen;
      for (const auto& k : keys) {
        if (!seen.insert(k).second) throw IoError(source, "landmark '" + k + "' appears more than once");
        unique_keys.push_back(k);
      }
      out.points = parse_plain_json(doc, unique_keys, source);
    }
  }
  validate(out.points, source, options);
  return out;
}

LandmarkSet landmarks_to_mm(const LandmarkSet& landmarks, mesh::Units undeclared_units) {
  double factor = mesh::to_mm_factor(undeclared_units);
  if (landmarks.declared_units) {
    if (*landmarks.declared_units == "mm") factor = 1.0;
    else if (*landmarks.declared_units == "m") factor = 1000.0;
    else throw InvalidInput("landmark units '" + *landmarks.declared_units + "' is not one of mm, m");
  }
  LandmarkSet out = landmarks;
  for (auto& p : out.points) p.position *= factor;
  out.declared_units = "mm";
  return out;
}

}  // namespace breastfit::io
