#include "breastfit/serve/workspace.h"

#include <fstream>

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"
#include "support/test_paths.h"

namespace breastfit::serve {
namespace {
namespace fs = std::filesystem;

struct WorkspaceTest : ::testing::Test {
  fs::path dir = test::temp_dir();
  fs::path root = dir / "ws";
  void SetUp() override {
    fs::create_directories(root / "cases");
    std::ofstream(root / "cases" / "scan.ply") << "ply";
    std::ofstream(dir / "secret.txt") << "patient";
  }
};

TEST_F(WorkspaceTest, ResolvesRelativePathsInside) {
  const Workspace ws(root);
  EXPECT_EQ(ws.existing_file("cases/scan.ply"), fs::canonical(root / "cases" / "scan.ply"));
  EXPECT_EQ(ws.resolve("out/new.mrk.json"), fs::canonical(root) / "out" / "new.mrk.json");
  EXPECT_EQ(ws.relative(ws.resolve("./cases//scan.ply")), "cases/scan.ply");
}

TEST_F(WorkspaceTest, RefusesAbsoluteDotDotBackslashAndEmpty) {
  const Workspace ws(root);
  for (const std::string bad : {"", "/etc/passwd", "../secret.txt", "cases/../../secret.txt", "cases\\scan.ply",
                                "..", "."})
    EXPECT_THROW(ws.resolve(bad), InvalidInput) << bad;
  try {
    ws.resolve("../secret.txt");
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("'..' is refused"), std::string::npos) << e.what();
  }
}

TEST_F(WorkspaceTest, RefusesSymlinksLeadingOut) {
  fs::create_symlink(dir / "secret.txt", root / "link.txt");
  fs::create_directory_symlink(dir, root / "up");
  fs::create_symlink(root / "cases" / "scan.ply", root / "inside.ply");
  const Workspace ws(root);
  EXPECT_THROW(ws.existing_file("link.txt"), InvalidInput);
  EXPECT_THROW(ws.resolve("up/secret.txt"), InvalidInput);
  EXPECT_THROW(ws.resolve("up/new.txt"), InvalidInput);  // not existing yet, but its parent leads out
  EXPECT_NO_THROW(ws.existing_file("inside.ply"));       // a link inside the workspace is fine
  const auto files = ws.list_files();
  EXPECT_EQ(files, (std::vector<std::string>{"cases/scan.ply", "inside.ply"}));
}

TEST_F(WorkspaceTest, MissingFilesAndDirectories) {
  const Workspace ws(root);
  EXPECT_THROW(ws.existing_file("cases/none.ply"), InvalidInput);
  EXPECT_THROW(ws.existing_file("cases"), InvalidInput);
  EXPECT_THROW(Workspace(root / "none"), IoError);
}

}  // namespace
}  // namespace breastfit::serve
