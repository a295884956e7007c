#include "breastfit/pipeline/register_outputs.h"

#include <fstream>
#include <functional>
#include <vector>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/core/task_queue.h"
#include "breastfit/io/io.h"
#include "breastfit/io/markups.h"
#include "breastfit/io/output_set.h"
#include "breastfit/model/params_json.h"
#include "breastfit/pipeline/register_report_json.h"
#include "breastfit/pipeline/report_html.h"
#include "breastfit/transfer/drawing_outputs.h"

namespace breastfit::pipeline {
namespace fs = std::filesystem;
namespace {

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (!fs::exists(a, ec) || !fs::exists(b, ec)) return false;
  return fs::equivalent(a, b, ec);
}

void write_json(const fs::path& path, const nlohmann::json& j) {
  std::ofstream f(path);
  if (!f) throw IoError(path.string(), "cannot open for writing");
  f << j.dump(1) << "\n";
  if (!f) throw IoError(path.string(), "write failed (disk full?)");
}

}  // namespace

std::vector<std::string> register_output_names() {
  return {"fitted.ply", "landmarks.mrk.json", "drawings.mrk.json", "drawings.ply", "drawings.obj",
          "scan_painted.ply", "params.json", "report.json", "report.html"};
}

void check_output_dir(const fs::path& dir, bool force, const std::vector<fs::path>& protected_paths) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw IoError(dir.string(), "exists and is not a directory");
  for (const auto& name : register_output_names()) {
    const fs::path p = dir / name;
    for (const auto& in : protected_paths)
      if (same_file(p, in)) throw IoError(p.string(), "is one of the inputs: choose another --out");
    if (!force && fs::exists(p, ec))
      throw IoError(p.string(), "already exists (use --force to replace the outputs)");
  }
}

void write_register_outputs(const fs::path& dir, const RegisterResult& r, const model::RiggedModel& model, bool force,
                            const std::vector<fs::path>& protected_paths, const RegisterOutputOptions& options) {
  check_output_dir(dir, force, protected_paths);
  io::OutputSet set(dir, register_output_names(), "report.json");

  // The files are written by up to three threads (two without report.html), each taking the
  // next group in order: report.html (rendering its figures is most of its cost), the painted
  // scan, the fitted model with the JSON files, and last the drawings' small meshes, for the
  // thread that is free first. The bytes are the same either way; the first group's error in
  // this order is rethrown once all have run.
  const double from_mm = 1.0 / r.scan.to_mm;
  std::vector<std::function<void()>> groups;
  if (options.report_html)
    groups.emplace_back([&] { write_report_html(set.path("report.html"), r, model, options.figures, options.layers); });
  groups.emplace_back(
      [&] { transfer::write_scan_painted(set.path("scan_painted.ply"), r.scan.mesh_mm, r.drawings_on_scan, from_mm); });
  groups.emplace_back([&] {
    TriangleMesh fitted = r.fitted_mm;
    fitted.V *= from_mm;
    io::write_mesh(set.path("fitted.ply"), fitted);

    io::MarkupsWriteOptions mo;
    mo.units = r.scan.units == mesh::Units::Metres ? "m" : "mm";
    io::MarkupsWriteOptions landmark_options = mo;  // not to be confused with the input landmarks
    landmark_options.points_name = kFittedLandmarksName;
    landmark_options.points_color = kFittedLandmarksColor;
    io::write_markups(set.path("landmarks.mrk.json"), r.model_landmarks_mm, landmark_options);
    io::write_markups(set.path("drawings.mrk.json"), r.drawings_mm, mo);

    nlohmann::json params = model::params_to_json(model, r.fit.params);
    params["template"] = {{"name", model.name}};
    if (const InputFile* t = r.provenance ? r.provenance->input("template") : nullptr) {
      params["template"]["path"] = t->path;
      params["template"]["sha256"] = t->sha256;
    }
    params["units_note"] = "translations in mm in the scan frame (converted from the file's units)";
    if (r.fit.detail_offsets.size() > 0)
      params["surface_detail"] = {
          {"note", "fitted.ply = the posed template + offsets_mm[i] * unit vertex normal i of the posed template"},
          {"offsets_mm", std::vector<double>(r.fit.detail_offsets.data(),
                                             r.fit.detail_offsets.data() + r.fit.detail_offsets.size())}};
    write_json(set.path("params.json"), params);
    write_json(set.path("report.json"), report_json(r));
  });
  groups.emplace_back([&] {
    transfer::write_drawings_ply(set.path("drawings.ply"), r.drawings_on_scan, from_mm);
    transfer::write_drawings_obj(set.path("drawings.obj"), r.drawings_on_scan, from_mm);
  });
  const unsigned threads = options.report_html ? 3 : 2;
  run_in_order(groups.size(), threads, [&](std::size_t g) { groups[g](); });
  set.commit();  // without report.html, the previous run's report.html goes
}

void write_register_failure(const fs::path& dir, const RegisterResult& r, bool force,
                            const std::vector<fs::path>& protected_paths) {
  check_output_dir(dir, force, protected_paths);
  io::OutputSet set(dir, register_output_names(), "report.json");
  write_json(set.path("report.json"), report_json(r));
  set.commit();
}

}  // namespace breastfit::pipeline
