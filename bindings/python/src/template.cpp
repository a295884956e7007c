// Template (the rigged model) and pose(template, params).
#include "bindings.h"
#include "breastfit/model/gltf_io.h"
#include "breastfit/model/param_layout.h"
#include "breastfit/model/params_json.h"
#include "breastfit/model/pose_evaluator.h"

namespace breastfit::python {
namespace {

const model::RiggedModel& rm(const Template& t) { return *t.model; }

}  // namespace

void bind_template(py::module_& m) {
  py::class_<Template>(m, "Template",
                       "The rigged template torso: rest mesh (mm, LPS), scalable bones, bounded blendshapes, "
                       "landmarks and drawings on its surface. Immutable; shared by every fit that uses it.")
      .def_static(
          "default", [] { return Template{template_from_python(py::none()), template_path_from_python(py::none())}; },
          "The shipped default template (default_torso.glb; $BREASTFIT_TEMPLATE overrides where it is looked for).")
      .def_static(
          "load",
          [](const std::filesystem::path& path) {
            py::gil_scoped_release release;
            return Template{std::make_shared<const model::RiggedModel>(model::load_gltf(path)), path};
          },
          py::arg("path"), "Loads a rigged template (.glb/.gltf). Raises OSError naming the file for any problem.")
      .def_property_readonly("name", [](const Template& t) { return rm(t).name; })
      .def_property_readonly(
          "vertices", [](const Template& t) { return to_array(rm(t).rest.V); }, "(n, 3) rest vertices, mm")
      .def_property_readonly("faces", [](const Template& t) { return to_array(rm(t).rest.F); }, "(m, 3) triangles")
      .def_property_readonly(
          "bones",
          [](const Template& t) {
            py::dict d;
            for (const auto& b : rm(t).bones) {
              py::dict bone;
              bone["parent"] = b.parent ? py::object(py::str(rm(t).bones[*b.parent].name)) : py::none();
              bone["pivot"] = to_array(b.pivot);
              bone["scale_lo"] = to_array(b.scale_lo);
              bone["scale_hi"] = to_array(b.scale_hi);
              d[py::str(b.name)] = bone;
            }
            return d;
          },
          "dict bone name → {parent (name or None), pivot (3,) mm, scale_lo (3,), scale_hi (3,)}, parents first")
      .def_property_readonly(
          "blendshapes",
          [](const Template& t) {
            py::dict d;
            for (const auto& b : rm(t).blendshapes) {
              py::dict shape;
              shape["lo"] = b.lo;
              shape["hi"] = b.hi;
              shape["vertices"] = py::array_t<std::int64_t>(static_cast<py::ssize_t>(b.vertices.size()),
                                                            std::vector<std::int64_t>(b.vertices.begin(), b.vertices.end()).data());
              shape["displacements"] = to_array(b.displacements);
              d[py::str(b.name)] = shape;
            }
            return d;
          },
          "dict blendshape name → {lo, hi (weight bounds), vertices (k,) indices, displacements (k, 3) mm at weight 1}")
      .def_property_readonly(
          "landmarks",
          [](const Template& t) {
            py::dict d;
            for (const auto& l : rm(t).landmarks) d[py::str(l.name)] = to_array(l.point.position(rm(t).rest.V, rm(t).rest.F));
            return d;
          },
          "dict landmark name → (3,) position on the rest surface, mm")
      .def_property_readonly(
          "drawings",
          [](const Template& t) {
            py::dict d;
            for (const auto& dr : rm(t).drawings) {
              Curve c{dr.name, dr.closed, Points(static_cast<Index>(dr.points.size()), 3)};
              for (size_t i = 0; i < dr.points.size(); ++i)
                c.points.row(static_cast<Index>(i)) = dr.points[i].position(rm(t).rest.V, rm(t).rest.F).transpose();
              d[py::str(dr.name)] = c;
            }
            return d;
          },
          "dict drawing name → Curve on the rest surface, mm")
      .def_property_readonly(
          "param_names",
          [](const Template& t) {
            const model::ParamLayout layout(rm(t));
            std::vector<std::string> names;
            for (int i = 0; i < layout.num_params(); ++i) names.push_back(layout.name(i));
            return names;
          },
          "the names pose() and Fit.params use (\"global.scale\", \"bone.<bone>.rotation.x\", \"shape.<blendshape>\", ...)")
      .def("__repr__", [](const Template& t) {
        return "<breastfit.Template '" + rm(t).name + "' " + std::to_string(rm(t).num_vertices()) + " vertices, " +
               std::to_string(rm(t).num_bones()) + " bones, " + std::to_string(rm(t).num_blendshapes()) +
               " blendshapes>";
      });

  m.def("_set_installed_template", &set_installed_template, py::arg("path"),
        "Internal: the installed package's default template file (see breastfit/__init__.py).");

  m.def(
      "pose",
      [](const Template& t, const py::handle& params) {
        const nlohmann::json doc = params.is_none() ? nlohmann::json::object() : json_from_python(params, "params");
        const model::PoseParams p = model::params_from_json(rm(t), doc);
        Points posed;
        {
          py::gil_scoped_release release;
          posed = model::pose_vertices(rm(t), p);
        }
        return to_array(posed);
      },
      py::arg("template"), py::arg("params") = py::none(),
      "The template's vertices (n, 3, mm) posed by `params`, a dict parameter name → value (Template.param_names; "
      "missing names keep the rest pose; a Fit's params work as they are). Raises ValueError for an unknown name or "
      "a value outside the bounds.");
}

}  // namespace breastfit::python
