#include "breastfit/io/output_set.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>

#include "breastfit/core/errors.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string read(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Names of the entries of `parent` that are staging directories.
int staging_dirs_in(const fs::path& parent) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(parent))
    if (e.path().filename().string().find(".breastfit-tmp-") != std::string::npos) ++n;
  return n;
}

const std::vector<std::string> kNames{"a.txt", "sub/b.txt", "c.txt", "report.json"};

TEST(OutputSet, TheCompleteSetAppearsOnlyOnCommit) {
  const fs::path dir = test::temp_dir() / "out";
  {
    OutputSet set(dir, kNames, "report.json");
    EXPECT_EQ(set.staging_dir().parent_path(), dir.parent_path());
    write(set.path("a.txt"), "A");
    write(set.path("sub/b.txt"), "B");
    write(set.path("report.json"), "{}");
    EXPECT_FALSE(fs::exists(dir / "a.txt"));
    set.commit();
  }
  EXPECT_EQ(read(dir / "a.txt"), "A");
  EXPECT_EQ(read(dir / "sub" / "b.txt"), "B");
  EXPECT_EQ(read(dir / "report.json"), "{}");
  EXPECT_FALSE(fs::exists(dir / "c.txt"));
  EXPECT_EQ(staging_dirs_in(dir.parent_path()), 0);
}

TEST(OutputSet, AFailureBeforeCommitLeavesTheDirectoryAsItWas) {
  const fs::path dir = test::temp_dir() / "out";
  fs::create_directories(dir);
  write(dir / "a.txt", "old");
  write(dir / "report.json", "old");
  try {
    OutputSet set(dir, kNames, "report.json");
    write(set.path("a.txt"), "new");
    throw std::runtime_error("the run fails");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(read(dir / "a.txt"), "old");
  EXPECT_EQ(read(dir / "report.json"), "old");
  EXPECT_EQ(staging_dirs_in(dir.parent_path()), 0);
}

TEST(OutputSet, StaleFilesOfThePreviousSetGoForeignFilesStay) {
  const fs::path dir = test::temp_dir() / "out";
  fs::create_directories(dir / "sub");
  for (const auto& n : kNames) write(dir / n, "old");
  write(dir / "notes.txt", "mine");
  write(dir / "sub" / "mine.txt", "mine");
  OutputSet set(dir, kNames, "report.json");
  write(set.path("report.json"), "failed");  // a failing run: only its report
  set.commit();
  EXPECT_EQ(read(dir / "report.json"), "failed");
  for (const char* n : {"a.txt", "sub/b.txt", "c.txt"}) EXPECT_FALSE(fs::exists(dir / n)) << n;
  EXPECT_EQ(read(dir / "notes.txt"), "mine");
  EXPECT_EQ(read(dir / "sub" / "mine.txt"), "mine");
}

// Writes `files` (name, text) through a set of kNames into `dir` and commits it.
void commit_set(const fs::path& dir, const std::vector<std::pair<std::string, std::string>>& files) {
  OutputSet set(dir, kNames, "report.json");
  for (const auto& [name, text] : files) write(set.path(name), text);
  set.commit();
}

ino_t inode(const fs::path& p) {
  struct stat st {};
  EXPECT_EQ(::stat(p.c_str(), &st), 0) << p;
  return st.st_ino;
}

// The previous set replaced in one step: DIR is a new directory holding the user's own files
// (the same inodes, not copies), with DIR's permissions.
TEST(OutputSet, ThePreviousDirectoryIsSwappedForTheNewOneKeepingTheUsersFiles) {
  const fs::path parent = test::temp_dir();
  const fs::path dir = parent / "out";
  fs::create_directories(dir / "sub" / "deeper");
  for (const auto& n : kNames) write(dir / n, "old");
  write(dir / "notes.txt", "mine");
  write(dir / "sub" / "deeper" / "mine.txt", "mine");
  fs::create_symlink("notes.txt", dir / "link.txt");
  fs::create_hard_link(dir / "notes.txt", parent / "notes_elsewhere.txt");
  fs::permissions(dir, fs::perms::owner_all, fs::perm_options::replace);
  const ino_t before = inode(dir);
  commit_set(dir, {{"a.txt", "new"}, {"report.json", "new"}});
  EXPECT_NE(inode(dir), before);  // swapped, not modified in place
  EXPECT_EQ(fs::status(dir).permissions(), fs::perms::owner_all);
  EXPECT_EQ(read(dir / "a.txt"), "new");
  EXPECT_EQ(read(dir / "report.json"), "new");
  for (const char* n : {"sub/b.txt", "c.txt"}) EXPECT_FALSE(fs::exists(dir / n)) << n;
  EXPECT_TRUE(fs::equivalent(dir / "notes.txt", parent / "notes_elsewhere.txt"));
  EXPECT_EQ(read(dir / "sub" / "deeper" / "mine.txt"), "mine");
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_EQ(read(dir / "link.txt"), "mine");
  EXPECT_EQ(staging_dirs_in(parent), 0);
}

// Where a swap would strand a shell in the removed directory, or replace a symbolic link by a
// directory, the files are moved into the existing directory instead.
TEST(OutputSet, AWorkingDirectoryOrALinkedDirectoryIsUpdatedInPlace) {
  const fs::path parent = test::temp_dir();
  const fs::path dir = parent / "out";
  fs::create_directories(dir);
  write(dir / "c.txt", "old");
  const fs::path cwd = fs::current_path();
  const ino_t before = inode(dir);
  fs::current_path(dir);
  commit_set(dir, {{"report.json", "in place"}});
  fs::current_path(cwd);
  EXPECT_EQ(inode(dir), before);
  EXPECT_EQ(read(dir / "report.json"), "in place");
  EXPECT_FALSE(fs::exists(dir / "c.txt"));

  fs::create_directory_symlink("out", parent / "linked");
  commit_set(parent / "linked", {{"report.json", "through the link"}});
  EXPECT_TRUE(fs::is_symlink(parent / "linked"));
  EXPECT_EQ(read(dir / "report.json"), "through the link");
  EXPECT_EQ(staging_dirs_in(parent), 0);
}

TEST(OutputSet, RemovesTheStagingDirectoriesOfKilledRuns) {
  const fs::path parent = test::temp_dir();
  const fs::path dir = parent / "out";
  fs::create_directories(parent / ".out.breastfit-tmp-99999-3");
  write(parent / ".out.breastfit-tmp-99999-3" / "a.txt", "partial");
  fs::create_directories(parent / ".other.breastfit-tmp-1-0");  // another directory's: kept
  write(parent / "out.txt", "x");
  {
    OutputSet set(dir / "", kNames, "report.json");  // a trailing separator names the same directory
    EXPECT_FALSE(fs::exists(parent / ".out.breastfit-tmp-99999-3"));
    EXPECT_EQ(staging_dirs_in(parent), 2);  // ours and the other directory's
  }
  EXPECT_TRUE(fs::exists(parent / ".other.breastfit-tmp-1-0"));
  EXPECT_TRUE(fs::exists(parent / "out.txt"));
  EXPECT_EQ(staging_prefix(dir), ".out.breastfit-tmp-");
}

TEST(OutputSet, NeedsTheMarkerAndKnownNames) {
  const fs::path dir = test::temp_dir() / "out";
  EXPECT_THROW(OutputSet(dir, kNames, "missing.json"), std::invalid_argument);
  OutputSet set(dir, kNames, "report.json");
  EXPECT_THROW(set.path("other.txt"), std::invalid_argument);
  write(set.path("a.txt"), "A");
  EXPECT_THROW(set.commit(), std::logic_error);  // no report.json: never an unmarked set
  EXPECT_FALSE(fs::exists(dir / "a.txt"));
}

TEST(OutputSet, LooseFilesAreStagedInsideTheirDirectoryAndMovedTogether) {
  const fs::path dir = test::temp_dir();
  write(dir / "a_front.png", "old front");
  write(dir / "a_side.png", "old side");
  fs::create_directories(dir / ".a_side.png.breastfit-tmp-99999-0");  // a killed run's, same marker
  fs::create_directories(dir / ".b.png.breastfit-tmp-99999-0");       // another set's: kept
  {
    OutputSet set = loose_file_set({dir / "a_front.png", dir / "a_side.png"});
    EXPECT_TRUE(fs::equivalent(set.staging_dir().parent_path(), dir));
    EXPECT_FALSE(fs::exists(dir / ".a_side.png.breastfit-tmp-99999-0"));
    write(set.path("a_front.png"), "new front");
    write(set.path("a_side.png"), "new side");
    EXPECT_EQ(read(dir / "a_front.png"), "old front");
    set.commit();
  }
  EXPECT_EQ(read(dir / "a_front.png"), "new front");
  EXPECT_EQ(read(dir / "a_side.png"), "new side");
  EXPECT_TRUE(fs::exists(dir / ".b.png.breastfit-tmp-99999-0"));
  EXPECT_EQ(staging_dirs_in(dir), 1);
  EXPECT_THROW(loose_file_set({dir / "a.png", dir / "sub" / "b.png"}), std::invalid_argument);
  EXPECT_THROW(loose_file_set({}), std::invalid_argument);
}

TEST(OutputSet, ACommitThatCannotMoveEveryFileMovesNone) {
  // The middle file's destination is a directory: the failure comes before any move.
  const fs::path dir = test::temp_dir();
  write(dir / "a.png", "old a");
  fs::create_directories(dir / "b.png");
  write(dir / "c.png", "old c");
  {
    OutputSet set = loose_file_set({dir / "a.png", dir / "b.png", dir / "c.png"});
    for (const char* n : {"a.png", "b.png", "c.png"}) write(set.path(n), "new");
    EXPECT_THROW(set.commit(), IoError);
  }
  EXPECT_EQ(read(dir / "a.png"), "old a");
  EXPECT_EQ(read(dir / "c.png"), "old c");
  EXPECT_TRUE(fs::is_directory(dir / "b.png"));
  EXPECT_EQ(staging_dirs_in(dir), 0);
}

}  // namespace
}  // namespace breastfit::io
