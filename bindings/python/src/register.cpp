// register(scan, landmarks, template, options) -> Fit: the pipeline's registration of one scan
// (pipeline::register_scan, what `breastfit register` runs) with the GIL released, and the Fit:
// its arrays, parameters, landmarks, drawings, report and save(dir) (the CLI's output set).
#include "bindings.h"
#include "breastfit/core/errors.h"
#include "breastfit/fit/fit_options_json.h"
#include "breastfit/io/landmarks_io.h"
#include "breastfit/mesh/landmark_names.h"
#include "breastfit/model/params_json.h"
#include "breastfit/pipeline/register_outputs.h"
#include "breastfit/pipeline/register_report_json.h"
#include "breastfit/pipeline/register_scan.h"
#include "fit_object.h"

namespace breastfit::python {
namespace {

/// Landmarks from a dict name → (3,) (in the scan's units) or a landmark file.
LandmarkSet landmarks_from_python(const py::handle& value, std::string& name, std::vector<std::filesystem::path>& inputs) {
  if (const auto path = path_from_python(value)) {
    name = *path;
    inputs.emplace_back(*path);
    py::gil_scoped_release release;
    return io::read_landmarks(*path);
  }
  if (!py::isinstance<py::dict>(value))
    throw InvalidInput("landmarks: expected a dict name → (3,) array, a landmark file path or None");
  LandmarkSet set;
  for (const auto& [k, v] : value.cast<py::dict>()) {
    if (!py::isinstance<py::str>(k)) throw InvalidInput("landmarks: names must be strings");
    const std::string n = k.cast<std::string>();
    if (!landmark_index(n)) throw InvalidInput("landmarks: unknown name '" + n + "' (expected one of " + landmark_name_list() + ")");
    set.points.push_back({n, vec3_from_array(v, "landmark '" + n + "'")});
  }
  if (set.points.empty()) throw InvalidInput("landmarks: the dict is empty (pass None for a landmark-free fit)");
  name = "<landmarks>";
  return set;
}

double to_units(const Fit& f) { return 1.0 / f.result.scan.to_mm; }

}  // namespace

void bind_register(py::module_& m) {
  py::class_<TransferredDrawing>(m, "Drawing",
                                 "A template drawing transferred onto the scan: points (n, 3) in the scan's units, "
                                 "one support flag per point (True: on the scan; False: the fitted model's point, "
                                 "where the scan has a hole or border).")
      .def_readonly("name", &TransferredDrawing::name)
      .def_readonly("closed", &TransferredDrawing::closed)
      .def_property_readonly("points", [](const TransferredDrawing& d) { return to_array(d.points); })
      .def_property_readonly("supported", [](const TransferredDrawing& d) {
        py::array_t<bool> a(static_cast<py::ssize_t>(d.supported.size()));
        for (size_t i = 0; i < d.supported.size(); ++i) a.mutable_at(i) = d.supported[i];
        return a;
      }, "(n,) bool array")
      .def_readonly("supported_fraction", &TransferredDrawing::supported_fraction, "fraction of the points on the scan")
      .def_readonly("length", &TransferredDrawing::length, "polyline length in the scan's units")
      .def("__repr__", [](const TransferredDrawing& d) {
        return "<breastfit.Drawing '" + d.name + "' " + std::to_string(d.points.rows()) + " points, " +
               std::to_string(static_cast<int>(100 * d.supported_fraction + 0.5)) + "% supported>";
      });

  py::class_<Fit>(m, "Fit", "The result of register(): the fitted template on the scan, in the scan's frame and units.")
      .def_property_readonly("usable", [](const Fit& f) { return f.result.usable(); },
                             "whether the template came to lie on the scan (False: only report and save() are meaningful)")
      .def_property_readonly("status", [](const Fit& f) { return f.result.status(); },
                             "report.json's status: \"ok\", \"implausible\" (usable, but see .report[\"plausibility\"]) or \"not_usable\"")
      .def_property_readonly("message", [](const Fit& f) { return f.result.fit.summary.message; },
                             "one line: why the fit is not usable, or how the solver ended")
      .def_property_readonly("units", [](const Fit& f) { return std::string(mesh::units_name(f.result.scan.units)); },
                             "the scan's units (\"mm\" or \"m\"): every array of the Fit is in them")
      .def_property_readonly("vertices", [](const Fit& f) { return to_array(Points(f.result.fitted_mm.V * to_units(f))); },
                             "(n, 3) fitted template vertices (with surface detail), as fitted.ply")
      .def_property_readonly("faces", [](const Fit& f) { return to_array(f.result.fitted_mm.F); }, "(m, 3) the template's triangles")
      .def_property_readonly(
          "params",
          [](const Fit& f) { return python_from_json(model::params_to_json(*f.model, f.result.fit.params)["params"]); },
          "dict parameter name → value (as params.json; pose(template, params) gives the posed template without "
          "surface detail, in mm)")
      .def_property_readonly(
          "landmarks",
          [](const Fit& f) {
            py::dict d;
            for (const auto& p : f.result.model_landmarks_mm.points) d[py::str(p.name)] = to_array(Vec3(p.position * to_units(f)));
            return d;
          },
          "dict name → (3,): the template's landmarks on the fitted model (landmarks.mrk.json)")
      .def_property_readonly(
          "drawings",
          [](const Fit& f) {
            py::dict d;
            for (const auto& c : f.result.drawings_on_scan) d[py::str(c.name)] = transferred_drawing(c, to_units(f));
            return d;
          },
          "dict name → Drawing: breast contours, sternum and folds transferred onto the scan (drawings.mrk.json)")
      .def_property_readonly("report", [](const Fit& f) { return python_from_json(pipeline::report_json(f.result)); },
                             "report.json as a dict (times, solver, Table 1 errors, drawings, breast measurements, warnings)")
      .def_property_readonly("warnings", [](const Fit& f) { return f.result.warnings; })
      .def_property_readonly("time_s", [](const Fit& f) { return f.result.time_s; },
                             "scan in memory → fitted parameters, seconds")
      .def_property_readonly("template", [](const Fit& f) { return Template{f.model, f.template_path}; })
      .def(
          "save",
          [](const Fit& f, const std::filesystem::path& dir, bool force, bool report_html) {
            py::gil_scoped_release release;
            if (!f.result.usable()) {
              pipeline::write_register_failure(dir, f.result, force, f.inputs);
              return;
            }
            pipeline::RegisterOutputOptions o;
            o.report_html = report_html;
            pipeline::write_register_outputs(dir, f.result, *f.model, force, f.inputs, o);
          },
          py::arg("dir"), py::arg("force") = false, py::arg("report_html") = true,
          "Writes the output set of `breastfit register` into `dir` (created): fitted.ply, landmarks.mrk.json, "
          "drawings.mrk.json, drawings.ply/.obj, scan_painted.ply, params.json, report.json, report.html — or only "
          "report.json when the fit is not usable. Raises OSError when an output exists (without force) or cannot "
          "be written.")
      .def("__repr__", [](const Fit& f) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "<breastfit.Fit %s, surface error %.2f mm, %.2f s>",
                      f.result.usable() ? "usable" : "NOT usable", f.result.surface.mae, f.result.time_s);
        return std::string(buf);
      });

  m.def(
      "register",
      [](const py::handle& scan, const py::handle& landmarks, const py::handle& template_, const py::handle& options,
         const py::handle& units) {
        auto fit = std::make_unique<Fit>();
        pipeline::RegisterRequest req;
        req.scan = mesh_from_python(scan, "scan", &req.scan_name);
        if (const auto path = path_from_python(scan)) fit->inputs.emplace_back(*path);
        req.units = units_from_python(units);
        if (!landmarks.is_none()) req.landmarks = landmarks_from_python(landmarks, req.landmarks_name, fit->inputs);
        req.model = template_from_python(template_);
        if (!options.is_none()) fit::update_from_json(req.options, json_from_python(options, "options"));
        fit->model = req.model;
        fit->template_path = template_path_from_python(template_);
        {
          const auto path = [](const py::handle& h) {
            const auto p = path_from_python(h);
            return p ? std::filesystem::path(*p) : std::filesystem::path();
          };
          req.provenance = provenance_from_python(
              {{"scan", path(scan)}, {"landmarks", path(landmarks)}, {"template", fit->template_path}});
        }
        {
          py::gil_scoped_release release;
          fit->result = pipeline::register_scan(req);
        }
        return fit;
      },
      py::arg("scan"), py::arg("landmarks") = py::none(), py::arg("template") = py::none(),
      py::arg("options") = py::none(), py::arg("units") = "auto",
      R"(Registers the template to a scan (what `breastfit register` does) and returns a Fit.

scan       a Mesh, a (vertices, faces) pair of arrays (faces None: a point cloud) or a mesh file path
landmarks  None (landmark-free), a dict name → (3,) array in the scan's units (names: nipple_R,
           sternal_notch, ...), or a landmark file (.mrk.json .json .csv .fcsv)
template   a Template (default: the shipped one)
options    a dict of fit options, the JSON of `--config` (docs/REGISTRATION.md), e.g.
           {"use_landmarks": False} or {"weights": {"lambda_data": 0.5}}
units      "auto" (from the scan's extent), "mm" or "m"

The GIL is released while fitting: threads can fit several scans at once. A fit that does not come
to lie on the scan is returned with usable False. Raises ValueError for bad arrays, landmarks or
options, OSError for a file that cannot be read.)");
}

}  // namespace breastfit::python
