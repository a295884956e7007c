#include "breastfit/pipeline/provenance.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "breastfit/core/errors.h"
#include "breastfit/pipeline/provenance_json.h"
#include "support/test_paths.h"

namespace breastfit::pipeline {
namespace {

TEST(Provenance, VersionTimeAndCommandLine) {
  EXPECT_EQ(breastfit_version().rfind("0.", 0), 0u) << breastfit_version();
  EXPECT_TRUE(std::regex_match(utc_now_iso8601(), std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")))
      << utc_now_iso8601();
  EXPECT_EQ(shell_command_line({"breastfit", "register", "scan.ply", "--out", "a/b"}),
            "breastfit register scan.ply --out a/b");
  EXPECT_EQ(shell_command_line({"x", "my scan.ply", "it's", ""}), "x 'my scan.ply' 'it'\\''s' ''");
}

TEST(Provenance, InputsAreHashedAndOnlyTheRunBlockVaries) {
  const auto path = test::temp_dir() / "abc.txt";
  std::ofstream(path) << "abc";
  Provenance p;
  p.version = breastfit_version();
  p.inputs.push_back(hash_input("scan", path));
  EXPECT_EQ(p.inputs[0].sha256, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  ASSERT_NE(p.input("scan"), nullptr);
  EXPECT_EQ(p.input("template"), nullptr);
  EXPECT_THROW(hash_input("scan", test::temp_dir() / "missing.ply"), IoError);

  Provenance q = p;
  q.started_utc = "2030-01-01T00:00:00Z";
  q.command_line = "breastfit register other";
  EXPECT_EQ(provenance_json(p), provenance_json(q));
  EXPECT_NE(run_json(p), run_json(q));
  const auto j = provenance_json(p);
  EXPECT_EQ(j["inputs"]["scan"]["path"], path.string());
  EXPECT_TRUE(j["fit_options"].is_object());
  EXPECT_FALSE(j.contains("started_utc"));
}

}  // namespace
}  // namespace breastfit::pipeline
