// numpy ↔ Eigen with validation, Python ↔ JSON, units and paths (bindings.h).
#include <cmath>
#include <cstdlib>

#include "bindings.h"
#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/model/gltf_io.h"
#include "breastfit/model/template_library.h"

namespace breastfit::python {
namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

py::array as_array(const py::handle& value, const std::string& what) {
  py::array a = py::array::ensure(value);
  if (!a) throw InvalidInput(what + ": not an array");
  return a;
}

}  // namespace

Points points_from_array(const py::handle& value, const std::string& what) {
  py::array raw = py::array::ensure(value);
  if (!raw) throw InvalidInput(what + ": not an array (expected an (n, 3) array of floats)");
  const char kind = raw.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw InvalidInput(what + ": expected numbers, got dtype " + std::string(py::str(raw.dtype())));
  if (raw.ndim() != 2 || raw.shape(1) != 3)
    throw InvalidInput(what + ": expected shape (n, 3), got " + shape_text(raw));
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(raw);
  const auto r = a.unchecked<2>();
  Points p(a.shape(0), 3);
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (int k = 0; k < 3; ++k) {
      const double x = r(i, k);
      if (!std::isfinite(x))
        throw InvalidInput(what + ": row " + std::to_string(i) + " is not finite (" + std::to_string(x) + ")");
      p(i, k) = x;
    }
  return p;
}

Triangles triangles_from_array(const py::handle& value, Index num_vertices, const std::string& what) {
  py::array raw = py::array::ensure(value);
  if (!raw) throw InvalidInput(what + ": not an array (expected an (m, 3) array of integers)");
  const char kind = raw.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw InvalidInput(what + ": expected integer vertex indices, got dtype " + std::string(py::str(raw.dtype())));
  if (raw.ndim() != 2 || raw.shape(1) != 3)
    throw InvalidInput(what + ": expected shape (m, 3), got " + shape_text(raw));
  const auto a = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(raw);
  const auto r = a.unchecked<2>();
  Triangles f(a.shape(0), 3);
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t v = r(i, k);
      if (v < 0 || v >= num_vertices)
        throw InvalidInput(what + ": face " + std::to_string(i) + " has vertex index " + std::to_string(v) +
                           ", outside [0, " + std::to_string(num_vertices) + ")");
      f(i, k) = static_cast<Index>(v);
    }
  return f;
}

Vec3 vec3_from_array(const py::handle& value, const std::string& what) {
  const py::array a = as_array(value, what);
  if (a.size() != 3 || a.ndim() > 2) throw InvalidInput(what + ": expected 3 coordinates, got shape " + shape_text(a));
  const Points p = points_from_array(a.attr("reshape")(1, 3), what);
  return p.row(0).transpose();
}

py::array_t<double> to_array(const Points& p) {
  py::array_t<double> a({static_cast<py::ssize_t>(p.rows()), py::ssize_t{3}});
  std::copy(p.data(), p.data() + p.size(), a.mutable_data());
  return a;
}

py::array_t<double> to_array(const Vec3& v) {
  py::array_t<double> a(py::ssize_t{3});
  std::copy(v.data(), v.data() + 3, a.mutable_data());
  return a;
}

py::array_t<std::int64_t> to_array(const Triangles& f) {
  py::array_t<std::int64_t> a({static_cast<py::ssize_t>(f.rows()), py::ssize_t{3}});
  std::copy(f.data(), f.data() + f.size(), a.mutable_data());
  return a;
}

std::optional<std::string> path_from_python(const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__fspath__")) return py::str(value.attr("__fspath__")()).cast<std::string>();
  return std::nullopt;
}

std::vector<Curve> curves_from_dict(const py::handle& dict, const std::string& what) {
  std::vector<Curve> out;
  for (const auto& [k, v] : dict.cast<py::dict>()) {
    const std::string name = py::str(k);
    Curve c = py::isinstance<Curve>(v) ? v.cast<Curve>() : Curve{name, false, points_from_array(v, what + " '" + name + "'")};
    c.name = name;
    out.push_back(std::move(c));
  }
  return out;
}

TriangleMesh mesh_from_python(const py::handle& value, const std::string& what, std::string* name) {
  if (py::isinstance<TriangleMesh>(value)) {
    if (name) *name = "<" + what + ">";
    return value.cast<TriangleMesh>();
  }
  if (const auto path = path_from_python(value)) {
    if (name) *name = *path;
    py::gil_scoped_release release;
    return io::read_mesh(*path);
  }
  if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
    const py::sequence seq = py::reinterpret_borrow<py::sequence>(value);
    if (seq.size() != 2) throw InvalidInput(what + ": expected (vertices, faces), got " + std::to_string(seq.size()) + " items");
    TriangleMesh mesh;
    mesh.V = points_from_array(seq[0], what + " vertices");
    if (!seq[1].is_none()) mesh.F = triangles_from_array(seq[1], mesh.num_vertices(), what + " faces");
    if (name) *name = "<" + what + ">";
    return mesh;
  }
  throw InvalidInput(what + ": expected a Mesh, a (vertices, faces) pair or a file path, got " +
                     std::string(py::str(value.get_type().attr("__name__"))));
}

nlohmann::json json_from_python(const py::handle& value, const std::string& what) {
  std::string text;
  try {
    text = py::module_::import("json").attr("dumps")(value, py::arg("allow_nan") = false).cast<std::string>();
  } catch (const py::error_already_set& e) {
    throw InvalidInput(what + ": not representable as JSON (" + std::string(e.what()) + ")");
  }
  return nlohmann::json::parse(text);
}

py::object python_from_json(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

std::optional<mesh::Units> units_from_python(const py::handle& value) {
  if (value.is_none()) return std::nullopt;
  if (!py::isinstance<py::str>(value)) throw InvalidInput("units: expected \"auto\", \"mm\" or \"m\"");
  const std::string u = value.cast<std::string>();
  if (u == "auto") return std::nullopt;
  if (u == "mm") return mesh::Units::Millimetres;
  if (u == "m") return mesh::Units::Metres;
  throw InvalidInput("units: expected \"auto\", \"mm\" or \"m\", got \"" + u + "\"");
}

namespace {
std::filesystem::path& installed_template() {
  static std::filesystem::path path;
  return path;
}

// The shipped default template's file: the installed one next to the package, unless
// BREASTFIT_TEMPLATE names another (model::default_template_path() honours it).
std::filesystem::path default_template_file() {
  const char* env = std::getenv("BREASTFIT_TEMPLATE");
  const bool installed = (!env || !*env) && !installed_template().empty();
  return installed ? installed_template() : model::default_template_path();
}

const Template& template_argument(const py::handle& value) {
  if (!py::isinstance<Template>(value)) throw InvalidInput("template: expected a breastfit.Template or None");
  return value.cast<const Template&>();
}
}  // namespace

void set_installed_template(const std::filesystem::path& path) { installed_template() = path; }

std::shared_ptr<const model::RiggedModel> template_from_python(const py::handle& value) {
  if (value.is_none()) {
    // The shipped default, loaded once per process (a template is immutable and shared).
    static std::shared_ptr<const model::RiggedModel> default_model;
    if (!default_model) {
      std::shared_ptr<const model::RiggedModel> loaded;
      {
        py::gil_scoped_release release;
        loaded = std::make_shared<const model::RiggedModel>(model::load_gltf(default_template_file()));
      }
      if (!default_model) default_model = std::move(loaded);  // another thread may have been first
    }
    return default_model;
  }
  return template_argument(value).model;
}

std::filesystem::path template_path_from_python(const py::handle& value) {
  return value.is_none() ? default_template_file() : template_argument(value).path;
}

pipeline::Provenance provenance_from_python(const std::vector<std::pair<std::string, std::filesystem::path>>& files) {
  std::vector<std::string> args{"python3"};
  for (const py::handle& a : py::module_::import("sys").attr("argv")) args.push_back(py::str(a));
  return pipeline::start_provenance(pipeline::shell_command_line(args), files);
}

}  // namespace breastfit::python
