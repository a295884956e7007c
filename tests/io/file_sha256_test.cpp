#include "breastfit/io/file_sha256.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "breastfit/core/errors.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

TEST(FileSha256, KnownDigests) {
  // FIPS 180-2 test vectors.
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(FileSha256, FileOfSeveralChunksEqualsTheBytesDigest) {
  std::string bytes;
  for (int i = 0; i < 200000; ++i) bytes += static_cast<char>(i * 7 % 251);
  const auto path = test::temp_dir() / "data.bin";
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_EQ(file_sha256_hex(path), sha256_hex(bytes));
  EXPECT_THROW(file_sha256_hex(test::temp_dir() / "missing.bin"), IoError);
  EXPECT_THROW(file_sha256_hex(test::temp_dir()), IoError);
}

}  // namespace
}  // namespace breastfit::io
