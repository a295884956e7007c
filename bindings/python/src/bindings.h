#pragma once
/// \file What the binding's files share: numpy ↔ Eigen conversions with validation, Python ↔
/// JSON, the template handle, and one bind_* function per bound concept (each in its own file).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "breastfit/core/types.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/mesh/units.h"
#include "breastfit/model/rigged_model.h"
#include "breastfit/pipeline/provenance.h"

namespace breastfit::python {
namespace py = pybind11;

/// A loaded template, shared (never copied) by every fit that uses it.
struct Template {
  std::shared_ptr<const model::RiggedModel> model;
  std::filesystem::path path;  ///< the file it was loaded from (report.json's provenance); empty: unknown
};

/// An (n, 3) float array as points. \throws InvalidInput (→ ValueError) naming `what` for another
/// shape, a non-numeric dtype or a NaN/Inf value
Points points_from_array(const py::handle& array, const std::string& what);
/// An (m, 3) integer array as triangles with every index in [0, num_vertices).
/// \throws InvalidInput naming `what` for another shape, a non-integer dtype or an index out of range
Triangles triangles_from_array(const py::handle& array, Index num_vertices, const std::string& what);
/// A (3,) float array (or sequence) as a point. \throws InvalidInput as points_from_array
Vec3 vec3_from_array(const py::handle& value, const std::string& what);

/// Copies into a new numpy array.
py::array_t<double> to_array(const Points& p);
py::array_t<double> to_array(const Vec3& v);
py::array_t<std::int64_t> to_array(const Triangles& f);

/// Curves from a dict name → Curve or (n, 3) array (an open curve), named by the keys.
/// \throws InvalidInput naming `what` and the curve for a bad array
std::vector<Curve> curves_from_dict(const py::handle& dict, const std::string& what);

/// A mesh from a Mesh object, a (vertices, faces) pair or a path (read from the file).
/// `name` receives the path for a file (messages, reports), else "<what>".
TriangleMesh mesh_from_python(const py::handle& value, const std::string& what, std::string* name = nullptr);

/// Python object (dict, list, numbers, strings) ↔ JSON, through Python's json module.
nlohmann::json json_from_python(const py::handle& value, const std::string& what);
py::object python_from_json(const nlohmann::json& j);

/// "auto"/None → nullopt, "mm", "m". \throws InvalidInput for anything else
std::optional<mesh::Units> units_from_python(const py::handle& value);

/// A str or os.PathLike as a path string, nullopt for anything else.
std::optional<std::string> path_from_python(const py::handle& value);

/// Where an installed module finds the shipped template (<prefix>/share/breastfit/default_torso.glb,
/// set by breastfit/__init__.py when that file exists): used for the default template unless
/// $BREASTFIT_TEMPLATE is set; otherwise model::default_template_path()'s search applies.
void set_installed_template(const std::filesystem::path& path);

/// The template a call uses: `value` (a Template) or the shipped default when None (loaded once).
std::shared_ptr<const model::RiggedModel> template_from_python(const py::handle& value);
/// The file of the template `template_from_python(value)` gives: the shipped default's for None,
/// the Template's own path otherwise (empty when unknown).
std::filesystem::path template_path_from_python(const py::handle& value);
/// The provenance of a fit started now from Python: the command line is the interpreter's
/// sys.argv; `files` as pipeline::start_provenance. Call with the GIL held.
pipeline::Provenance provenance_from_python(const std::vector<std::pair<std::string, std::filesystem::path>>& files);

/// Maps the library's exceptions to Python's (the only place that does).
void register_exceptions(py::module_& m);
void bind_mesh_io(py::module_& m);
void bind_template(py::module_& m);
void bind_register(py::module_& m);
void bind_transfer(py::module_& m);
void bind_cohort(py::module_& m);
void bind_landmarks(py::module_& m);

}  // namespace breastfit::python
