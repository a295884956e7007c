// landmarks(scan) -> dict: the 12 landmarks found automatically (pipeline/detect_landmarks.h, what
// `breastfit landmarks` runs), each with its position in the scan's units, a confidence and how it
// was found.
#include "bindings.h"
#include "breastfit/fit/fit_options_json.h"
#include "breastfit/pipeline/detect_landmarks.h"

namespace breastfit::python {

void bind_landmarks(py::module_& m) {
  m.def(
      "landmarks",
      [](const py::handle& scan, const py::handle& template_, const py::handle& options, const py::handle& units) {
        pipeline::RegisterRequest req;
        req.scan = mesh_from_python(scan, "scan", &req.scan_name);
        req.units = units_from_python(units);
        req.model = template_from_python(template_);
        if (!options.is_none()) fit::update_from_json(req.options, json_from_python(options, "options"));
        pipeline::DetectedLandmarks found;
        {
          py::gil_scoped_release release;
          found = pipeline::detect_landmarks(std::move(req));
        }
        const double to_units = 1.0 / found.registration.scan.to_mm;
        py::dict out;
        for (const auto& l : found.landmarks) {
          py::dict entry;
          entry["position"] = to_array(Vec3(l.position_mm * to_units));
          entry["confidence"] = l.confidence;
          entry["method"] = l.method;
          out[py::str(l.name)] = entry;
        }
        return out;
      },
      py::arg("scan"), py::arg("template") = py::none(), py::arg("options") = py::none(), py::arg("units") = "auto",
      R"(The template's landmarks found on a scan without any given (what `breastfit landmarks` does).

scan      a Mesh, a (vertices, faces) pair of arrays or a mesh file path
template  a Template (default: the shipped one)
options   a dict of fit options (the JSON of `--config`)
units     "auto" (from the scan's extent), "mm" or "m"

Returns a dict name → {"position": (3,) array in the scan's units, "confidence": float in [0, 1],
"method": how it was found}. A landmark-free fit, then each landmark snapped onto the scan (the
nipples at the breast tips, the lowest breast points at the folds when found): a starting point to
check and correct, then pass to register(). Raises ValueError when the landmark-free fit is not
usable or the input is bad, OSError for a file that cannot be read.)");
}

}  // namespace breastfit::python
