#include "breastfit/io/write_stl.h"

#include <gtest/gtest.h>

#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/io/read_stl.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

TriangleMesh tetra() {
  TriangleMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1.5, 0, 0, 0, 2.25, 0, 0, 0, -0.125;
  m.F.resize(4, 3);
  m.F << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2;
  return m;
}

TEST(WriteStl, BinaryAndAsciiRoundTripsReproduceTheIndexedMesh) {
  const TriangleMesh m = tetra();
  for (bool binary : {true, false}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    const std::string bytes = write_stl_to_memory(m, {.binary = binary});
    if (binary) {
      EXPECT_EQ(bytes.size(), 84u + 50u * 4u);
    }
    const TriangleMesh r = read_stl_from_memory(bytes, "rt.stl");
    EXPECT_EQ(r.V, m.V);  // first-seen order equals the original order here
    EXPECT_EQ(r.F, m.F);
  }
}

TEST(WriteStl, AsciiStartsWithSolidAndHasFacetNormals) {
  const std::string text = write_stl_to_memory(tetra(), {.binary = false});
  EXPECT_EQ(text.rfind("solid", 0), 0u);
  EXPECT_NE(text.find("facet normal 0 0 1"), std::string::npos);
}

TEST(WriteStl, FileRoundTrip) {
  const auto path = test::temp_dir() / "t.stl";
  write_stl(path, tetra());
  EXPECT_EQ(read_stl(path).F, tetra().F);
}

}  // namespace
}  // namespace breastfit::io
