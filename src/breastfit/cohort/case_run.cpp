#include "breastfit/cohort/case_run.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "breastfit/cohort/case_record_json.h"
#include "breastfit/core/errors.h"
#include "breastfit/core/timer.h"
#include "breastfit/io/io.h"
#include "breastfit/io/landmarks_io.h"
#include "breastfit/model/template_library.h"
#include "breastfit/pipeline/provenance.h"
#include "breastfit/pipeline/register_outputs.h"
#include "breastfit/pipeline/register_report_json.h"
#include "breastfit/pipeline/register_scan.h"

namespace breastfit::cohort {
namespace fs = std::filesystem;

fs::path case_output_dir(const fs::path& out_root, const CohortCase& c) { return out_root / c.name; }

std::optional<CaseRecord> finished_record(const fs::path& out_root, const CohortCase& c) {
  const fs::path report = case_output_dir(out_root, c) / "report.json";
  std::ifstream in(report);
  if (!in) return std::nullopt;
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return std::nullopt;  // a damaged report: fit again
  try {
    CaseRecord r = case_record_from_report(c.name, c.scan.string(), j);
    r.resumed = true;
    return r;
  } catch (const InvalidInput&) {
    return std::nullopt;
  }
}

CaseRecord run_case(const CohortCase& c, const fs::path& out_root, const CaseRunOptions& options) {
  if (!options.force)
    if (auto done = finished_record(out_root, c)) return *done;
  const Timer timer;
  CaseRecord record;
  record.name = c.name;
  record.scan = c.scan.string();
  try {
    pipeline::RegisterRequest req;
    req.scan = io::read_mesh(c.scan);
    req.scan_name = c.scan.string();
    req.units = options.units;
    std::vector<fs::path> inputs{c.scan};
    if (c.landmarks && !options.ignore_landmarks) {
      req.landmarks = io::read_landmarks(*c.landmarks);
      req.landmarks_name = c.landmarks->string();
      inputs.push_back(*c.landmarks);
    }
    req.model = options.model ? options.model
                               : std::make_shared<const model::RiggedModel>(model::load_default_template());
    req.options = options.fit;
    if (options.ignore_landmarks) req.options.use_landmarks = false;
    req.provenance = pipeline::start_provenance(
        options.command_line,
        {{"scan", c.scan},
         {"landmarks", inputs.size() > 1 ? inputs[1] : fs::path()},
         {"template", !options.template_path.empty() ? options.template_path
                      : options.model            ? fs::path()
                                                 : model::default_template_path()}});
    const pipeline::RegisterResult result = pipeline::register_scan(req);
    const fs::path dir = case_output_dir(out_root, c);
    // force: what is in `dir` is an unfinished run's (a finished one was returned above).
    if (result.usable()) {
      pipeline::RegisterOutputOptions out;
      out.report_html = options.report_html;
      pipeline::write_register_outputs(dir, result, *req.model, /*force=*/true, inputs, out);
    } else {
      pipeline::write_register_failure(dir, result, /*force=*/true, inputs);
    }
    record = case_record_from_report(c.name, c.scan.string(), pipeline::report_json(result));
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {  // InvalidInput, IoError, and anything else: this case only
    record.status = "failed";
    record.message = e.what();
  }
  record.wall_s = timer.seconds();
  return record;
}

}  // namespace breastfit::cohort
