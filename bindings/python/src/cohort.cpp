// The cohort layer for breastfit.cohort (Dask): cases, one case's run, cohort.csv/.html. The same
// library code as `breastfit batch`, so both give the same outputs.
#include "bindings.h"
#include "breastfit/cohort/batch.h"
#include "breastfit/cohort/case_record_json.h"
#include "breastfit/cohort/case_run.h"
#include "breastfit/cohort/cohort_case.h"
#include "breastfit/fit/fit_options_json.h"

namespace breastfit::python {

void bind_cohort(py::module_& m) {
  m.def(
      "resolve_cases",
      [](const std::vector<std::filesystem::path>& arguments) {
        py::list out;
        for (const cohort::CohortCase& c : cohort::resolve_cases(arguments))
          out.append(py::make_tuple(c.name, c.scan.string(), c.landmarks ? py::object(py::str(c.landmarks->string())) : py::none()));
        return out;
      },
      py::arg("arguments"),
      "The cases named by CASE arguments, as (name, scan, landmarks or None) tuples (docs/COHORTS.md: a scan "
      "file with a sibling <stem>.mrk.json, a case directory, or a directory of case directories). Raises "
      "OSError for a missing argument, ValueError for two cases with the same name.");
  m.def(
      "run_case",
      [](const std::string& name, const std::filesystem::path& scan, const std::optional<std::filesystem::path>& landmarks,
         const std::filesystem::path& out_root, const py::handle& template_, const py::handle& options,
         const py::handle& units, bool force, bool report_html, bool ignore_landmarks) {
        cohort::CaseRunOptions o;
        o.model = template_from_python(template_);
        o.template_path = template_path_from_python(template_);
        o.command_line = provenance_from_python({}).command_line;
        if (!options.is_none()) fit::update_from_json(o.fit, json_from_python(options, "options"));
        o.units = units_from_python(units);
        o.force = force;
        o.report_html = report_html;
        o.ignore_landmarks = ignore_landmarks;
        cohort::CaseRecord r;
        {
          py::gil_scoped_release release;
          r = cohort::run_case(cohort::CohortCase{name, scan, landmarks}, out_root, o);
        }
        return python_from_json(cohort::to_json(r));
      },
      py::arg("name"), py::arg("scan"), py::arg("landmarks"), py::arg("out_root"), py::arg("template") = py::none(),
      py::arg("options") = py::none(), py::arg("units") = "auto", py::arg("force") = false,
      py::arg("report_html") = true, py::arg("ignore_landmarks") = false,
      "Registers one case into out_root/name (as `breastfit batch` does; a previous run's finished case is "
      "returned as it is unless force) and returns its record as a dict (the columns of cohort.csv). A bad case "
      "is a record with status \"failed\", never an exception.");
  m.def(
      "write_cohort_summary",
      [](const std::filesystem::path& out_root, const py::handle& records) {
        std::vector<cohort::CaseRecord> rs;
        for (const auto& r : records.cast<py::list>()) rs.push_back(cohort::case_record_from_json(json_from_python(r, "record")));
        py::gil_scoped_release release;
        cohort::write_cohort_summary(out_root, rs);
      },
      py::arg("out_root"), py::arg("records"),
      "Writes out_root/cohort.csv and out_root/cohort.html from run_case's records (in the given order).");
}

}  // namespace breastfit::python
