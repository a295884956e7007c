#include "breastfit/synth/case_writer.h"

#include <cstdio>
#include <fstream>
#include <system_error>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/io/markups.h"
#include "breastfit/io/output_set.h"

namespace breastfit::synth {
namespace {

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", x == 0.0 ? 0.0 : x);  // no "-0"
  return buf;
}

std::string point(const Vec3& p) {
  std::string s = "[";
  s.append(num(p.x())).append(", ").append(num(p.y())).append(", ").append(num(p.z())).append("]");
  return s;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  return out + "\"";
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw IoError(path.string(), "cannot open for writing");
  f << text;
  f.close();
  if (!f) throw IoError(path.string(), "write failed");
}

std::string markups_text(const std::vector<NamedPoint>& points, const std::string& units) {
  Markups m;
  m.points = points;
  io::MarkupsWriteOptions o;
  o.units = units;
  return io::format_markups(m, o, units);
}

}  // namespace

std::string format_landmarks_json(const SynthCase& c) {
  std::string s = "{\n";
  for (size_t i = 0; i < c.truth_landmarks.size(); ++i) {
    s += " " + quoted(c.truth_landmarks[i].name) + ": " + point(c.truth_landmarks[i].position);
    s += i + 1 < c.truth_landmarks.size() ? ",\n" : "\n";
  }
  return s + "}\n";
}

std::string format_curves_json(const SynthCase& c) {
  std::string s = "{";
  for (size_t i = 0; i < c.truth_curves.size(); ++i) {
    const Curve& cv = c.truth_curves[i];
    s += (i ? ",\n " : "\n ") + quoted(cv.name) + ": {\"closed\": " + (cv.closed ? "true" : "false") + ", \"points\": [";
    for (Index k = 0; k < cv.points.rows(); ++k) {
      if (k) s += ", ";
      s += point(cv.points.row(k).transpose());
    }
    s += "]}";
  }
  return s + "\n}\n";
}

std::vector<std::string> case_file_names() {
  return {"scan.ply",          "landmarks.mrk.json",          "truth/surface.ply", "truth/landmarks.json",
          "truth/curves.json", "truth/landmarks.mrk.json", "truth/meta.json"};
}

void write_case(const std::filesystem::path& dir, const SynthCase& c, bool force) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!force && (fs::exists(dir / "scan.ply", ec) || fs::exists(dir / "truth", ec)))
    throw IoError(dir.string(), "a case already exists here (use --force to overwrite it)");
  io::OutputSet set(dir, case_file_names(), "truth/meta.json");

  io::MeshWriteOptions mo;
  mo.binary = true;
  TriangleMesh scan;
  scan.V = c.scan.V;
  scan.F = c.scan.F;
  io::write_mesh(set.path("scan.ply"), scan, mo);
  write_text(set.path("landmarks.mrk.json"), markups_text(c.input_landmarks, c.units));
  TriangleMesh truth;
  truth.V = c.truth_surface.V;
  truth.F = c.truth_surface.F;
  io::write_mesh(set.path("truth/surface.ply"), truth, mo);
  write_text(set.path("truth/landmarks.json"), format_landmarks_json(c));
  write_text(set.path("truth/curves.json"), format_curves_json(c));
  write_text(set.path("truth/landmarks.mrk.json"), markups_text(c.truth_landmarks, c.units));
  write_text(set.path("truth/meta.json"), c.meta_json);
  set.commit();
}

}  // namespace breastfit::synth
