#include "breastfit/transfer/fit_directory.h"

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/fit/surface_detail.h"
#include "breastfit/io/io.h"
#include "breastfit/model/params_json.h"
#include "breastfit/model/pose_evaluator.h"

namespace breastfit::transfer {
namespace fs = std::filesystem;
namespace {

nlohmann::json read_json_file(const fs::path& path) {
  std::ifstream f(path);
  if (!f) throw IoError(path.string(), "cannot be opened");
  try {
    return nlohmann::json::parse(f);
  } catch (const nlohmann::json::exception& e) {
    throw IoError(path.string(), std::string("not valid JSON: ") + e.what());
  }
}

// The surface-detail offsets of params.json (empty when the fit has none).
Eigen::VectorXd detail_offsets(const nlohmann::json& doc, const fs::path& path, Index num_vertices) {
  const auto it = doc.find("surface_detail");
  if (it == doc.end()) return {};
  const auto off = it->find("offsets_mm");
  if (!it->is_object() || off == it->end() || !off->is_array())
    throw IoError(path.string(), "\"surface_detail\" must be an object with an array \"offsets_mm\"");
  if (static_cast<Index>(off->size()) != num_vertices)
    throw IoError(path.string(), "\"surface_detail.offsets_mm\" has " + std::to_string(off->size()) +
                                     " values, the template " + std::to_string(num_vertices) +
                                     " vertices: the fit was made with another template (pass it with --template)");
  Eigen::VectorXd h(num_vertices);
  for (Index i = 0; i < num_vertices; ++i) {
    const auto& v = (*off)[i];
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      throw IoError(path.string(), "\"surface_detail.offsets_mm\"[" + std::to_string(i) + "] is not a finite number");
    h[i] = v.get<double>();
  }
  return h;
}

}  // namespace

FitDirectory read_fit_directory(const fs::path& dir, const model::RiggedModel* model) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw IoError(dir.string(), "is not a directory (expected the --out of `breastfit register`)");
  FitDirectory out;
  out.dir = dir;
  const fs::path report = dir / "report.json";
  if (!fs::exists(report, ec))
    throw IoError(dir.string(), "incomplete output set: no report.json (the run that wrote it was interrupted, or "
                                "this is not the --out of `breastfit register`)");
  const nlohmann::json j = read_json_file(report);
  if (j.is_object() && j.value("status", "") == "not_usable")
    throw IoError(report.string(), "the registration was not usable (status \"not_usable\"): there is no fit to read");
  if (j.contains("units")) {
    if (!j["units"].is_string() || (j["units"] != "mm" && j["units"] != "m"))
      throw IoError(report.string(), "\"units\" must be \"mm\" or \"m\"");
    out.units = j["units"].get<std::string>();
  }
  out.to_mm = out.units == "m" ? 1000.0 : 1.0;

  const fs::path ply = dir / "fitted.ply";
  const fs::path params = dir / "params.json";
  const bool has_ply = fs::exists(ply, ec);
  TriangleMesh from_file;
  if (has_ply) {
    from_file = io::read_mesh(ply);
    from_file.V *= out.to_mm;
  }
  if (model && fs::exists(params, ec)) {
    const nlohmann::json doc = read_json_file(params);
    model::PoseParams p;
    try {
      p = model::params_from_json(*model, doc);
    } catch (const InvalidInput& e) {
      throw InvalidInput(params.string() + ": " + e.what());
    }
    out.fitted_mm.V = model::pose_vertices(*model, p);
    out.fitted_mm.F = model->rest.F;
    const Eigen::VectorXd offsets = detail_offsets(doc, params, out.fitted_mm.V.rows());
    if (offsets.size() > 0) out.fitted_mm.V = fit::apply_surface_detail(out.fitted_mm.V, out.fitted_mm.F, offsets);
    out.from_params = true;
    if (has_ply) {
      if (from_file.V.rows() != out.fitted_mm.V.rows() || from_file.F.rows() != out.fitted_mm.F.rows())
        throw IoError(ply.string(), "has " + std::to_string(from_file.V.rows()) + " vertices, the template " +
                                        std::to_string(out.fitted_mm.V.rows()) +
                                        ": the fit was made with another template (pass it with --template)");
      const double extent = (out.fitted_mm.V.colwise().maxCoeff() - out.fitted_mm.V.colwise().minCoeff()).maxCoeff();
      const double dev = (from_file.V - out.fitted_mm.V).rowwise().norm().maxCoeff();
      if (!(dev <= 0.5 + 1e-5 * extent))
        throw IoError(ply.string(), "differs from the template posed by params.json by up to " + std::to_string(dev) +
                                        " mm: the fit was made with another template (pass it with --template)");
    }
    return out;
  }
  if (!has_ply) throw IoError(ply.string(), "missing (neither fitted.ply nor params.json with a template)");
  out.fitted_mm = std::move(from_file);
  out.fitted_mm.N.resize(0, 3);
  if (out.fitted_mm.num_faces() == 0) throw IoError(ply.string(), "has no triangles");
  return out;
}

}  // namespace breastfit::transfer
