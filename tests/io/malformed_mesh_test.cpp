// Every kind of bad mesh file must give an IoError with a one-line message naming the file and
// the problem — never a crash, a hang or a huge allocation. The bad files are generated here.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/io/read_obj.h"
#include "breastfit/io/read_ply.h"
#include "breastfit/io/read_stl.h"
#include "breastfit/io/read_vtk.h"
#include "breastfit/io/read_vtp.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

struct BadFile {
  std::string file;      // name inside temp_dir(); the extension picks the reader
  std::string content;   // bytes
  std::string expected;  // substring the problem must contain
};

template <typename T>
std::string bytes_of(std::initializer_list<T> values) {
  std::string s;
  for (T v : values) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    s.append(b, sizeof(T));
  }
  return s;
}

const std::string kPlyXyz = "property float x\nproperty float y\nproperty float z\n";
const std::string kPlyFace = "property list uchar int vertex_indices\n";
const std::string kAsciiHead = "ply\nformat ascii 1.0\nelement vertex 3\n" + kPlyXyz;
const std::string kBinHead = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + kPlyXyz;
const std::string kThreeVerts = "0 0 0\n1 0 0\n0 1 0\n";

std::string ascii_face(const std::string& face_line) {
  return kAsciiHead + "element face 1\n" + kPlyFace + "end_header\n" + kThreeVerts + face_line +
         "\n";
}

std::string binary_verts() { return bytes_of<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}); }

std::string binary_stl(std::uint32_t announced, std::size_t actual_triangles, float x0 = 0) {
  std::string s(80, ' ');
  s += bytes_of<std::uint32_t>({announced});
  for (std::size_t t = 0; t < actual_triangles; ++t) {
    s += bytes_of<float>({0, 0, 1, x0, 0, 0, 1, 0, 0, 0, 1, 0});
    s.append(2, '\0');
  }
  return s;
}

const std::string kFacetStart = "solid s\nfacet normal 0 0 1\nouter loop\n";

std::vector<BadFile> bad_files() {
  std::vector<BadFile> cases = {
      // ---- PLY
      {"empty.ply", "", "empty file"},
      {"text.ply", "hello world\nthis is not a mesh\n", "not a PLY file"},
      {"no_newline.ply", "ply", "truncated header"},
      {"truncated_header.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n",
       "no 'end_header'"},
      {"no_format.ply", "ply\nelement vertex 1\n" + kPlyXyz + "end_header\n0 0 0\n", "no 'format'"},
      {"bad_format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n",
       "unknown format 'binary_middle_endian'"},
      {"bad_type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
       "unknown property type 'float128'"},
      {"float_count.ply",
       "ply\nformat ascii 1.0\nelement face 1\nproperty list float int "
       "vertex_indices\nend_header\n",
       "not an integer type"},
      {"property_first.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n",
       "property before any element"},
      {"bad_keyword.ply", "ply\nformat ascii 1.0\nelephant vertex 3\nend_header\n",
       "unexpected keyword 'elephant'"},
      {"huge_count_text.ply",
       "ply\nformat ascii 1.0\nelement vertex 99999999999999999999\n" + kPlyXyz + "end_header\n",
       "bad element line"},
      {"no_vertex_element.ply",
       "ply\nformat ascii 1.0\nelement point 1\n" + kPlyXyz + "end_header\n0 0 0\n",
       "no 'vertex' element"},
      {"zero_vertices.ply", "ply\nformat ascii 1.0\nelement vertex 0\n" + kPlyXyz + "end_header\n",
       "no vertices"},
      {"no_z.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 "
       "0\n",
       "lacks one of the properties x, y, z"},
      {"list_x.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\nproperty float "
       "y\nproperty float z\nend_header\n1 0 0 0\n",
       "'x' is a list"},
      {"billions.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n" + kPlyXyz +
           "end_header\n" + binary_verts(),
       "header announces 4000000000 'vertex' elements"},
      {"billions_faces.ply",
       kBinHead + "element face 3000000000\n" + kPlyFace + "end_header\n" + binary_verts(),
       "header announces 3000000000 'face' elements"},
      {"truncated_binary.ply", kBinHead + "end_header\n" + binary_verts().substr(0, 30),
       "header announces 3 'vertex'"},
      {"truncated_ascii.ply",
       kAsciiHead + "end_header\n0.000000 0.000000 0.000000\n1.000000 0.0000 0.0000\n",
       "the file ends inside vertex 2"},
      {"missing_face_data.ply",
       kBinHead + "element face 1\n" + kPlyFace + "end_header\n" + binary_verts() + '\xff' +
           bytes_of<std::int32_t>({0, 1, 2}),
       "announces a list of 255 entries"},
      {"nan.ply", kAsciiHead + "end_header\n0 0 0\nnan 0 0\n0 1 0\n",
       "vertex 1 has a non-finite coordinate (nan)"},
      {"inf_binary.ply",
       kBinHead + "end_header\n" +
           bytes_of<float>({0, 0, 0, 1, 0, 0, 0, std::numeric_limits<float>::infinity(), 0}),
       "vertex 2 has a non-finite coordinate (inf)"},
      {"bad_token.ply", kAsciiHead + "end_header\n0 abc 0\n1 0 0\n0 1 0\n",
       "line 8: bad value 'abc' for property 'y' of vertex 0"},
      {"index_out_of_range.ply", ascii_face("3 0 1 9000"),
       "face 0 references vertex 9000 but the file has 3 vertices"},
      {"negative_index.ply", ascii_face("3 0 -1 2"), "face 0 references vertex -1"},
      {"fractional_index.ply", ascii_face("3 0 1.5 2"), "bad value '1.5'"},
      {"face0.ply", ascii_face("0"), "face 0 has 0 vertex indices (a face needs at least 3)"},
      {"face1.ply", ascii_face("1 0"), "face 0 has 1 vertex index (a face needs at least 3)"},
      {"face2.ply", ascii_face("2 0 1"), "face 0 has 2 vertex indices (a face needs at least 3)"},
      {"count_too_big_for_type.ply", ascii_face("256 0 1 2"), "bad value '256'"},
      {"negative_list.ply",
       kAsciiHead + "element face 1\nproperty list int int vertex_indices\nend_header\n" +
           kThreeVerts + "-5 0 1 2\n",
       "negative list length"},
      {"no_index_list.ply",
       kAsciiHead + "element face 1\nproperty int a\nend_header\n" + kThreeVerts + "7\n",
       "no 'vertex_indices'"},
      {"two_vertex_elements.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\n" + kPlyXyz + "element vertex 1\n" + kPlyXyz +
           "end_header\n0 0 0\n0 0 0\n",
       "two 'vertex' elements"},
      // ---- OBJ
      {"empty.obj", "", "empty file"},
      {"text.obj", "hello world\nthis is just prose.\n", "no vertices ('v' statements) found"},
      {"binary.obj",
       std::string("\x7f"
                   "ELF\0\0\x01v 1 2 3",
                   12),
       "NUL bytes"},
      {"short_vertex.obj", "v 1 2\n", "line 1: a vertex needs 3 coordinates, found 2"},
      {"bad_number.obj", "v 1 2 x3\n", "bad number 'x3' in a 'v' statement"},
      {"overflow.obj", "v 1e999 0 0\n", "bad number '1e999'"},
      {"nan.obj", "v 0 0 0\nv nan 0 0\n", "line 2: vertex 2 has a non-finite coordinate (nan)"},
      {"inf.obj", "v 0 0 -inf\n", "non-finite coordinate (-inf)"},
      {"out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9000\n",
       "line 4: face references vertex 9000 but 3 vertices are defined so far"},
      {"zero_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "vertex index 0 is invalid"},
      {"negative_too_far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -5\n",
       "face references vertex -5"},
      {"face0.obj", "v 0 0 0\nf\n", "face has 0 vertices (a face needs at least 3)"},
      {"face1.obj", "v 0 0 0\nf 1\n", "face has 1 vertex (a face needs at least 3)"},
      {"face2.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "face has 2 vertices (a face needs at least 3)"},
      {"bad_vt_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/9 3/1\n",
       "texture coordinate 9 but 1 texture coordinate is defined"},
      {"bad_vn_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n",
       "normal 1 but 0 normals are defined"},
      {"garbage_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/a 2 3\n",
       "bad texture coordinate index 'a'"},
      {"huge_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n",
       "bad vertex index '99999999999999999999'"},
      {"extra_slash.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n",
       "bad face corner '1/1/1/1'"},
      {"bad_vt.obj", "v 0 0 0\nvt nan 0\n", "non-finite texture coordinate"},
      // ---- STL
      {"empty.stl", "", "empty file"},
      {"text.stl", "hello world\n", "too short for a binary STL (12 bytes, need at least 84)"},
      {"lying_count.stl", binary_stl(5, 2), "binary STL header announces 5 triangles"},
      {"billions.stl", binary_stl(0xffffffffu, 1), "announces 4294967295 triangles"},
      {"nan_binary.stl", binary_stl(1, 1, std::numeric_limits<float>::quiet_NaN()),
       "triangle 0 has a non-finite coordinate (nan)"},
      {"no_triangles.stl", "solid empty\nendsolid empty\n", "no triangles"},
      {"no_triangles_binary.stl", binary_stl(0, 0), "no triangles"},
      {"truncated_ascii.stl", kFacetStart + "vertex 0 0 0\nvertex 1 0 0\n", "ends inside a facet"},
      {"two_vertex_facet.stl",
       kFacetStart + "vertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n",
       "facet 0 has 2 vertices"},
      {"bad_coordinate.stl", kFacetStart + "vertex 0 0 zero\n",
       "line 4: bad vertex coordinate 'zero'"},
      {"missing_coordinate.stl", kFacetStart + "vertex 0 0\n", "bad vertex coordinate ''"},
      {"nan_ascii.stl", kFacetStart + "vertex 0 nan 0\n", "non-finite vertex coordinate 'nan'"},
      {"vertex_outside.stl", "solid s\nvertex 0 0 0\n", "'vertex' outside an 'outer loop'"},
      {"garbage_ascii.stl", "solid s\nthis is not stl\n", "unexpected 'this'"},
  };
  return cases;
}

TEST(MalformedMesh, EachBadFileGivesAOneLineIoErrorNamingFileAndProblem) {
  const auto dir = test::temp_dir();
  for (const BadFile& bad : bad_files()) {
    SCOPED_TRACE(bad.file);
    const auto path = dir / bad.file;
    {
      std::ofstream out(path, std::ios::binary);
      out.write(bad.content.data(), static_cast<std::streamsize>(bad.content.size()));
    }
    try {
      read_mesh(path);
      ADD_FAILURE() << "no exception";
    } catch (const IoError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
      EXPECT_NE(e.problem().find(bad.expected), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_EQ(e.path(), path.string());
    } catch (const std::exception& e) {
      ADD_FAILURE() << "wrong exception type: " << e.what();
    }
  }
}

TEST(MalformedMesh, RandomBytesWithEachExtensionAreRejected) {
  const auto dir = test::temp_dir();
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 50; ++trial) {
    std::string bytes(static_cast<std::size_t>(rng() % 2000), '\0');
    for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
    for (const char* ext : {".ply", ".obj", ".stl"}) {
      const auto path = dir / ("random" + std::to_string(trial) + ext);
      {
        std::ofstream out(path, std::ios::binary);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      }
      EXPECT_THROW(read_mesh(path), IoError) << path;
    }
  }
}

TEST(MalformedMesh, TruncatingAValidFileAtEveryByteNeverCrashes) {
  // Every prefix of a valid file either reads (e.g. ascii cut after the last value) or throws
  // IoError; nothing else escapes.
  const std::string ply = kBinHead + "element face 1\n" + kPlyFace + "end_header\n" +
                          binary_verts() + '\x03' + bytes_of<std::int32_t>({0, 1, 2});
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\n";
  const std::string stl =
      kFacetStart + "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
  int ok = 0;
  for (std::size_t n = 0; n < ply.size(); ++n) {
    try {
      read_ply_from_memory(ply.substr(0, n), "p.ply");
      ++ok;
    } catch (const IoError&) {
    }
  }
  EXPECT_EQ(ok, 0) << "a binary PLY cut short is always incomplete";
  EXPECT_EQ(read_ply_from_memory(ply, "p.ply").num_faces(), 1);
  for (std::size_t n = 0; n <= obj.size(); ++n) {
    try {
      read_obj_from_memory(obj.substr(0, n), "o.obj");
    } catch (const IoError&) {
    }
  }
  for (std::size_t n = 0; n <= stl.size(); ++n) {
    try {
      read_stl_from_memory(stl.substr(0, n), "s.stl");
    } catch (const IoError&) {
    }
  }
  EXPECT_EQ(read_stl_from_memory(stl, "s.stl").num_faces(), 1);
}

TEST(MalformedMesh, OddButValidInputsAreAccepted) {
  // Degenerate faces (repeated index) are dropped, not errors.
  const TriangleMesh obj =
      read_obj_from_memory("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\nf 1 2 3\n", "d.obj");
  EXPECT_EQ(obj.num_faces(), 1);
  // An element without properties costs nothing, whatever its count.
  const TriangleMesh ply = read_ply_from_memory(
      kAsciiHead + "element nothing 1000000000000\nend_header\n" + kThreeVerts, "n.ply");
  EXPECT_EQ(ply.num_vertices(), 3);
  // Trailing bytes after the declared data are ignored.
  EXPECT_EQ(read_ply_from_memory(kBinHead + "end_header\n" + binary_verts() + "junk", "t.ply")
                .num_vertices(),
            3);
}

/// Crash/hang/allocation regressions found by the fuzzers (fuzz/), kept as files: each must read
/// or throw IoError — nothing else.
TEST(MalformedMesh, FuzzRegressionsReadOrThrowIoError) {
  const auto root = test::data_dir() / "fuzz";
  ASSERT_TRUE(std::filesystem::is_directory(root));
  int files = 0;
  for (const auto& [sub, reader] :
       std::vector<std::pair<std::string, TriangleMesh (*)(std::string_view, const std::string&)>>{
           {"ply", &read_ply_from_memory},
           {"obj", &read_obj_from_memory},
           {"stl", &read_stl_from_memory},
           {"vtk", &read_vtk_from_memory},
           {"vtp", &read_vtp_from_memory}}) {
    if (!std::filesystem::is_directory(root / sub)) continue;
    for (const auto& entry : std::filesystem::directory_iterator(root / sub)) {
      if (!entry.is_regular_file() || entry.path().filename().string().front() == '.') continue;
      std::ifstream in(entry.path(), std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
      ++files;
      try {
        const TriangleMesh m = reader(bytes, entry.path().filename().string());
        EXPECT_GT(m.num_vertices(), 0) << entry.path();
        if (m.num_faces() > 0) {
          EXPECT_GE(m.F.minCoeff(), 0) << entry.path();
          EXPECT_LT(m.F.maxCoeff(), m.num_vertices()) << entry.path();
        }
        EXPECT_TRUE(m.V.allFinite()) << entry.path();
      } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << entry.path();
      }
    }
  }
  RecordProperty("fuzz_regression_files", files);
}

}  // namespace
}  // namespace breastfit::io
