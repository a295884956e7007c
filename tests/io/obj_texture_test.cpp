#include "breastfit/io/obj_texture.h"

#include <fstream>

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {
namespace fs = std::filesystem;

fs::path write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
  return p;
}

TEST(ObjTexture, FindsTheImageThroughTheMaterialLibrary) {
  const fs::path dir = test::temp_dir();
  const fs::path obj = write(dir / "scan.obj", "# scanner\nmtllib  mat/scan.mtl\r\nv 0 0 0\nusemtl skin\nf 1 1 1\n");
  write(dir / "mat" / "scan.mtl", "newmtl skin\nKd 1 1 1\n  map_Kd -s 1 1 1 -clamp on -imfchan r skin photo.jpg\n");
  const ObjTexture t = obj_texture(obj);
  EXPECT_EQ(t.mtl, dir / "mat" / "scan.mtl");
  EXPECT_EQ(t.image, dir / "mat" / "skin photo.jpg");  // relative to the library; a space in the name kept
  EXPECT_TRUE(t.problem.empty());
}

TEST(ObjTexture, NoLibraryMissingLibraryNoImage) {
  const fs::path dir = test::temp_dir();
  const ObjTexture none = obj_texture(write(dir / "plain.obj", "v 0 0 0\nf 1 1 1\n"));
  EXPECT_TRUE(none.mtl.empty());
  EXPECT_TRUE(none.image.empty());
  EXPECT_TRUE(none.problem.empty());
  const ObjTexture missing = obj_texture(write(dir / "a.obj", "mtllib gone.mtl\n"));
  EXPECT_TRUE(missing.image.empty());
  EXPECT_NE(missing.problem.find("gone.mtl is missing"), std::string::npos) << missing.problem;
  write(dir / "flat.mtl", "newmtl skin\nKd 0.8 0.6 0.5\nmap_Kdx nope.png\n");
  const ObjTexture flat = obj_texture(write(dir / "b.obj", "mtllib flat.mtl\n"));
  EXPECT_TRUE(flat.image.empty());
  EXPECT_NE(flat.problem.find("map_Kd"), std::string::npos) << flat.problem;
  EXPECT_THROW(obj_texture(dir / "nothing.obj"), IoError);
}

}  // namespace
}  // namespace breastfit::io
