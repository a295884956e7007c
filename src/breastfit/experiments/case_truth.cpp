#include "breastfit/experiments/case_truth.h"

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/io/landmarks_io.h"

namespace breastfit::experiments {
namespace {

namespace fs = std::filesystem;

nlohmann::json read_json(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw IoError(path.string(), "cannot be read");
  std::stringstream s;
  s << f.rdbuf();
  try {
    return nlohmann::json::parse(s.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw IoError(path.string(), std::string("malformed JSON: ") + e.what());
  }
}

std::optional<nlohmann::json> read_meta(const fs::path& case_dir) {
  const fs::path p = case_dir / "truth" / "meta.json";
  if (!fs::is_regular_file(p)) return std::nullopt;
  nlohmann::json j = read_json(p);
  if (!j.is_object()) throw IoError(p.string(), "is not a JSON object");
  return j;
}

}  // namespace

std::optional<std::string> read_truth_units(const fs::path& case_dir) {
  const auto meta = read_meta(case_dir);
  if (!meta || !meta->contains("units")) return std::nullopt;
  const auto& u = (*meta)["units"];
  if (!u.is_string() || (u != "mm" && u != "m"))
    throw IoError((case_dir / "truth" / "meta.json").string(), "\"units\" must be \"mm\" or \"m\"");
  return u.get<std::string>();
}

std::optional<std::string> read_truth_pose(const fs::path& case_dir) {
  const auto meta = read_meta(case_dir);
  if (!meta || !meta->contains("pose")) return std::nullopt;
  const auto& p = (*meta)["pose"];
  if (p.is_object() && p.contains("type") && p["type"].is_string()) return p["type"].get<std::string>();
  if (p.is_string()) return p.get<std::string>();
  return std::nullopt;
}

std::vector<Curve> read_truth_curves(const fs::path& path, double to_mm) {
  const nlohmann::json j = read_json(path);
  if (!j.is_object()) throw IoError(path.string(), "is not a JSON object {name: {closed, points}}");
  std::vector<Curve> out;
  for (const auto& [name, c] : j.items()) {
    if (!c.is_object() || !c.contains("points") || !c["points"].is_array())
      throw IoError(path.string(), "curve '" + name + "' has no \"points\" array");
    Curve curve;
    curve.name = name;
    curve.closed = c.value("closed", false);
    const auto& pts = c["points"];
    curve.points.resize(static_cast<Index>(pts.size()), 3);
    for (size_t i = 0; i < pts.size(); ++i) {
      const auto& p = pts[i];
      if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() || !p[2].is_number())
        throw IoError(path.string(), "curve '" + name + "' point " + std::to_string(i) + " is not [x, y, z]");
      for (int k = 0; k < 3; ++k) curve.points(static_cast<Index>(i), k) = p[k].get<double>() * to_mm;
    }
    if (curve.points.rows() < 2) throw IoError(path.string(), "curve '" + name + "' has fewer than 2 points");
    out.push_back(std::move(curve));
  }
  return out;
}

std::optional<CaseTruth> read_case_truth(const fs::path& case_dir, double to_mm) {
  const fs::path t = case_dir / "truth";
  const fs::path surface = t / "surface.ply", landmarks = t / "landmarks.json", curves = t / "curves.json";
  if (!fs::is_directory(t)) return std::nullopt;
  if (!fs::is_regular_file(surface) && !fs::is_regular_file(landmarks) && !fs::is_regular_file(curves))
    return std::nullopt;
  for (const auto& p : {surface, landmarks, curves})
    if (!fs::is_regular_file(p)) throw IoError(p.string(), "missing (the truth directory is incomplete)");
  CaseTruth truth;
  truth.surface_mm = io::read_mesh(surface);
  truth.surface_mm.V *= to_mm;
  const LandmarkSet lm = io::read_landmarks(landmarks);
  for (auto p : lm.points) {
    p.position *= to_mm;
    truth.landmarks_mm.push_back(p);
  }
  truth.curves_mm = read_truth_curves(curves, to_mm);
  return truth;
}

}  // namespace breastfit::experiments
