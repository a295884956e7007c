#include "breastfit/experiments/case_set.h"

#include <algorithm>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/io/landmarks_io.h"
#include "breastfit/pipeline/scan_input.h"

namespace breastfit::experiments {

namespace fs = std::filesystem;

std::vector<fs::path> find_case_dirs(const fs::path& dir, const std::vector<std::string>& only) {
  if (!fs::is_directory(dir)) throw IoError(dir.string(), "not a directory");
  std::vector<fs::path> all;
  if (fs::exists(dir / "scan.ply")) {
    all.push_back(dir);
  } else {
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_directory() && fs::exists(e.path() / "scan.ply")) all.push_back(e.path());
    std::sort(all.begin(), all.end());
  }
  if (all.empty()) throw IoError(dir.string(), "holds no case directory (a folder with scan.ply)");
  if (only.empty()) return all;
  for (const auto& id : only)
    if (std::none_of(all.begin(), all.end(), [&](const fs::path& p) { return p.filename() == id; }))
      throw IoError(dir.string(), "has no case '" + id + "'");
  std::vector<fs::path> out;
  for (const auto& p : all)
    if (std::find(only.begin(), only.end(), p.filename().string()) != only.end()) out.push_back(p);
  return out;
}

std::string case_pose(const fs::path& case_dir) {
  if (const auto p = read_truth_pose(case_dir)) return *p;
  const std::string id = case_dir.filename().string();
  if (id.find("supine") != std::string::npos) return "supine";
  if (id.find("standing") != std::string::npos) return "standing";
  return "unknown";
}

EvalCase load_case(const fs::path& case_dir) {
  EvalCase c;
  c.dir = case_dir;
  c.id = case_dir.filename().string();
  c.pose = case_pose(case_dir);
  const fs::path scan_path = case_dir / "scan.ply";
  c.scan = io::read_mesh(scan_path);
  if (const auto u = read_truth_units(case_dir))
    c.units = *u == "m" ? mesh::Units::Metres : mesh::Units::Millimetres;
  else
    c.units = pipeline::prepare_scan(c.scan, scan_path.string(), std::nullopt).units;
  c.to_mm = mesh::to_mm_factor(c.units);
  const fs::path lm = case_dir / "landmarks.mrk.json";
  if (fs::is_regular_file(lm)) {
    c.landmarks = io::read_landmarks(lm);
    c.landmarks_mm = pipeline::prepare_landmarks(*c.landmarks, c.units);
  }
  c.truth = read_case_truth(case_dir, c.to_mm);
  return c;
}

}  // namespace breastfit::experiments
