// `breastfit serve`: the command line's refusals (the server itself: tests/serve; the whole page in
// a browser, with Ctrl-C: the ctest serve.browser).
#include <gtest/gtest.h>

#include "support/test_paths.h"

namespace breastfit {
namespace {

TEST(ServeCommand, OtherHostsNeedAllowRemote) {
  std::string out;
  const int code = test::run_cli("serve --workspace " + test::temp_dir().string() + " --host 0.0.0.0 --port 0", &out);
  EXPECT_EQ(code, 3) << out;
  EXPECT_NE(out.find("--allow-remote"), std::string::npos) << out;
}

TEST(ServeCommand, TheWorkspaceMustExist) {
  std::string out;
  const int code = test::run_cli("serve --workspace " + (test::temp_dir() / "none").string() + " --port 0", &out);
  EXPECT_EQ(code, 4) << out;
  EXPECT_NE(out.find("workspace"), std::string::npos) << out;
}

}  // namespace
}  // namespace breastfit
