#pragma once
// One real registration shared by the report tests (report_html_test, report_figures_test):
// the shipped template fitted to a default synthetic case (seed 7, standing), computed once per
// test program.
#include "support/default_template.h"
#include "support/synth_request.h"
#include "breastfit/model/template_library.h"
#include "breastfit/pipeline/register_scan.h"
#include "breastfit/synth/synth_case.h"

namespace breastfit::test {

inline const model::RiggedModel& report_test_model() { return *test::default_template(); }

inline const pipeline::RegisterResult& report_test_result() {
  static const pipeline::RegisterResult r = [] {
    synth::SynthOptions o;
    o.seed = 7;
    pipeline::RegisterRequest req = synth_request(synth::make_case(report_test_model(), o));
    req.scan_name = "cases/synth <7>/scan.ply";  // a name that needs escaping in HTML
    return pipeline::register_scan(req);
  }();
  return r;
}

}  // namespace breastfit::test
