// Mapping a file read-only: its bytes as written, an empty file as no bytes, and the messages
// of the whole-file reader for a missing file or a directory.
#include "breastfit/io/detail/mapped_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/io/read_ply.h"
#include "support/test_paths.h"

namespace breastfit::io::detail {
namespace {

std::string message_of(const std::filesystem::path& path) {
  try {
    const MappedFile file(path);
  } catch (const IoError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MappedFile, BytesAsWrittenAndEmptyFile) {
  const auto dir = test::temp_dir();
  std::string bytes = "ply\n";
  for (int i = 0; i < 100000; ++i) bytes += static_cast<char>(i * 7);
  { std::ofstream(dir / "data.bin", std::ios::binary) << bytes; }
  const MappedFile file(dir / "data.bin");
  EXPECT_EQ(file.bytes(), bytes);
  { std::ofstream(dir / "empty.ply", std::ios::binary); }
  EXPECT_TRUE(MappedFile(dir / "empty.ply").bytes().empty());
  EXPECT_THROW(read_ply(dir / "empty.ply"), IoError);  // "empty file", not a crash
}

TEST(MappedFile, MissingFileAndDirectory) {
  const auto dir = test::temp_dir();
  EXPECT_EQ(message_of(dir / "missing.ply"), (dir / "missing.ply").string() + ": file does not exist");
  std::filesystem::create_directories(dir / "folder.ply");
  EXPECT_EQ(message_of(dir / "folder.ply"),
            (dir / "folder.ply").string() + ": is a directory, not a mesh file");
}

}  // namespace
}  // namespace breastfit::io::detail
