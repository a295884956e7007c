#include "breastfit/transfer/fit_directory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/fit/surface_detail.h"
#include "breastfit/io/io.h"
#include "breastfit/model/params_json.h"
#include "breastfit/model/pose_evaluator.h"
#include "support/test_paths.h"
#include "support/toy_model.h"

namespace breastfit::transfer {
namespace {

namespace fs = std::filesystem;

TEST(FitDirectory, ReadsParamsOrFittedPlyInTheReportUnits) {
  const model::RiggedModel m = test::make_toy_model();
  const fs::path dir = test::temp_dir() / "fit";
  fs::create_directories(dir);
  const model::PoseParams p = test::random_toy_pose(m, 9, 0.5);
  model::write_params_json(dir / "params.json", m, p);
  TriangleMesh fitted;
  fitted.V = model::pose_vertices(m, p);
  fitted.F = m.rest.F;
  TriangleMesh in_m = fitted;
  in_m.V *= 0.001;
  io::write_mesh(dir / "fitted.ply", in_m);
  std::ofstream(dir / "report.json") << R"({"units": "m", "time_s": 0.2})";

  const FitDirectory exact = read_fit_directory(dir, &m);
  EXPECT_TRUE(exact.from_params);
  EXPECT_EQ(exact.units, "m");
  EXPECT_DOUBLE_EQ(exact.to_mm, 1000.0);
  EXPECT_LT((exact.fitted_mm.V - fitted.V).cwiseAbs().maxCoeff(), 1e-9);  // posed in double precision
  EXPECT_TRUE(exact.fitted_mm.F == fitted.F);

  const FitDirectory from_ply = read_fit_directory(dir);  // no template: fitted.ply in mm
  EXPECT_FALSE(from_ply.from_params);
  EXPECT_LT((from_ply.fitted_mm.V - fitted.V).cwiseAbs().maxCoeff(), 0.05);  // float32 file

  // fitted.ply of another pose: refused with a template
  TriangleMesh other = in_m;
  other.V.array() += 0.01;  // 10 mm
  io::write_mesh(dir / "fitted.ply", other);
  EXPECT_THROW(read_fit_directory(dir, &m), IoError);
  fs::remove(dir / "fitted.ply");
  EXPECT_NO_THROW(read_fit_directory(dir, &m));  // params.json alone is enough with a template
  EXPECT_THROW(read_fit_directory(dir), IoError);  // ... but not without
  std::ofstream(dir / "report.json") << R"({"units": "inches"})";
  EXPECT_THROW(read_fit_directory(dir, &m), IoError);
  EXPECT_THROW(read_fit_directory(dir / "nope", &m), IoError);
}

TEST(FitDirectory, AppliesTheSurfaceDetailOfParamsJson) {
  const model::RiggedModel m = test::make_toy_model();
  const fs::path dir = test::temp_dir() / "fit_detail";
  fs::create_directories(dir);
  const model::PoseParams p = test::random_toy_pose(m, 4, 0.5);
  const Points posed = model::pose_vertices(m, p);
  Eigen::VectorXd offsets(posed.rows());
  for (Index i = 0; i < posed.rows(); ++i) offsets[i] = 2.0 * std::sin(0.1 * static_cast<double>(i));
  nlohmann::json doc = model::params_to_json(m, p);
  doc["surface_detail"] = {{"offsets_mm", std::vector<double>(offsets.data(), offsets.data() + offsets.size())}};
  std::ofstream(dir / "params.json") << doc.dump();
  TriangleMesh fitted;
  fitted.V = fit::apply_surface_detail(posed, m.rest.F, offsets);
  fitted.F = m.rest.F;
  io::write_mesh(dir / "fitted.ply", fitted);
  std::ofstream(dir / "report.json") << R"({"status": "ok", "units": "mm"})";

  const FitDirectory read = read_fit_directory(dir, &m);
  EXPECT_LT((read.fitted_mm.V - fitted.V).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT((read.fitted_mm.V - posed).cwiseAbs().maxCoeff(), 1.0);  // the offsets were applied

  doc["surface_detail"]["offsets_mm"] = std::vector<double>(3, 0.0);  // another template's count
  std::ofstream(dir / "params.json") << doc.dump();
  EXPECT_THROW(read_fit_directory(dir, &m), IoError);
  doc["surface_detail"] = {{"offsets_mm", "none"}};
  std::ofstream(dir / "params.json") << doc.dump();
  EXPECT_THROW(read_fit_directory(dir, &m), IoError);
}

TEST(FitDirectory, RefusesAnIncompleteSetAndANotUsableFit) {
  const model::RiggedModel m = test::make_toy_model();
  const fs::path dir = test::temp_dir() / "fit";
  fs::create_directories(dir);
  model::write_params_json(dir / "params.json", m, model::PoseParams::identity(m));
  const auto expect_refused = [&](const std::string& why) {
    try {
      read_fit_directory(dir, &m);
      ADD_FAILURE() << "accepted, expected: " << why;
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  // report.json is moved in last: without it the set is incomplete (an interrupted run).
  expect_refused("incomplete output set: no report.json");
  std::ofstream(dir / "report.json") << R"({"status": "not_usable", "units": "mm"})";
  expect_refused("not usable");
  std::ofstream(dir / "report.json") << R"({"status": "ok", "units": "mm"})";
  EXPECT_NO_THROW(read_fit_directory(dir, &m));
}

}  // namespace
}  // namespace breastfit::transfer
