#include "breastfit/cohort/batch.h"

#include <fstream>
#include <mutex>

#include "breastfit/cohort/cohort_csv.h"
#include "breastfit/cohort/cohort_html.h"
#include "breastfit/core/errors.h"
#include "breastfit/core/task_queue.h"
#include "breastfit/io/output_set.h"
#include "breastfit/model/template_library.h"

namespace breastfit::cohort {
namespace fs = std::filesystem;

std::vector<CaseRecord> run_batch(const std::vector<CohortCase>& cases, const fs::path& out_root,
                                  const BatchOptions& options, const BatchProgress& progress) {
  if (options.jobs < 1) throw InvalidInput("jobs must be at least 1 (got " + std::to_string(options.jobs) + ")");
  std::error_code ec;
  fs::create_directories(out_root, ec);
  if (ec) throw IoError(out_root.string(), "cannot create the output directory: " + ec.message());
  CaseRunOptions run = options.run;
  if (!run.model) run.model = std::make_shared<const model::RiggedModel>(model::load_default_template());
  // Cases run side by side use the cores; each fit on one thread unless asked otherwise (threads
  // only change the speed, never the result: fit/parallel_chunks.h).
  if (options.jobs > 1 && run.fit.threads == 0) run.fit.threads = 1;

  std::vector<CaseRecord> records(cases.size());
  std::mutex progress_mutex;
  int done = 0;
  run_in_order(cases.size(), static_cast<unsigned>(options.jobs), [&](size_t i) {
    records[i] = run_case(cases[i], out_root, run);
    const std::lock_guard lock(progress_mutex);
    ++done;
    if (progress) progress(done, static_cast<int>(cases.size()), records[i]);
  });
  return records;
}

namespace {

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  if (!f) throw IoError(path.string(), "cannot open for writing");
  f << text;
  if (!f) throw IoError(path.string(), "write failed");
}

}  // namespace

void write_cohort_summary(const fs::path& out_root, const std::vector<CaseRecord>& records) {
  io::OutputSet set = io::loose_file_set({out_root / "cohort.html", out_root / "cohort.csv"});
  write_text(set.path("cohort.html"), cohort_html(records));
  write_text(set.path("cohort.csv"), format_cohort_csv(records));
  set.commit();
}

}  // namespace breastfit::cohort
