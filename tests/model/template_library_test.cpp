#include "breastfit/model/template_library.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "breastfit/core/errors.h"
#include "breastfit/model/gltf_io.h"
#include "support/scoped_env.h"
#include "support/test_paths.h"
#include "support/toy_model.h"

namespace breastfit::model {
namespace {

/// BREASTFIT_TEMPLATE for the scope of a test, restored afterwards.
class ScopedTemplateEnv : public test::ScopedEnv {
 public:
  explicit ScopedTemplateEnv(const char* value) : ScopedEnv("BREASTFIT_TEMPLATE", value) {}
};

TEST(TemplateLibrary, EnvironmentVariableWins) {
  const auto file = test::temp_dir() / "toy.glb";
  save_gltf(file, test::make_toy_model());
  ScopedTemplateEnv env(file.c_str());
  const auto candidates = default_template_candidates();
  ASSERT_GE(candidates.size(), 3u);
  EXPECT_EQ(candidates.front(), file);
  EXPECT_EQ(default_template_path(), file);
  EXPECT_EQ(load_default_template().name, "toy");
}

TEST(TemplateLibrary, MissingEnvironmentFileIsAnErrorNotAFallback) {
  const auto missing = test::temp_dir() / "nope.glb";
  ScopedTemplateEnv env(missing.c_str());
  try {
    default_template_path();
    ADD_FAILURE() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("nope.glb"), std::string::npos) << e.what();
  }
}

TEST(TemplateLibrary, CandidatesWithoutEnvironment) {
  ScopedTemplateEnv env(nullptr);
  const auto candidates = default_template_candidates();
  ASSERT_EQ(candidates.size(), 2u);
  EXPECT_EQ(candidates[0].filename(), kDefaultTemplateFile);
  EXPECT_EQ(candidates[0].parent_path().filename(), "breastfit");
  EXPECT_EQ(candidates[1], test::source_dir() / "assets" / "templates" / kDefaultTemplateFile);
  // Either a shipped template is found or the error names the paths tried.
  try {
    const auto p = default_template_path();
    EXPECT_TRUE(std::filesystem::is_regular_file(p));
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("assets/templates"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace breastfit::model
