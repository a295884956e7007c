#include "breastfit/io/read_vtp.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "breastfit/core/errors.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < in.size(); i += 3) {
    const std::uint32_t b0 = static_cast<unsigned char>(in[i]);
    const std::uint32_t b1 = i + 1 < in.size() ? static_cast<unsigned char>(in[i + 1]) : 0;
    const std::uint32_t b2 = i + 2 < in.size() ? static_cast<unsigned char>(in[i + 2]) : 0;
    const std::uint32_t v = b0 << 16 | b1 << 8 | b2;
    out += k[v >> 18];
    out += k[(v >> 12) & 63];
    out += i + 1 < in.size() ? k[(v >> 6) & 63] : '=';
    out += i + 2 < in.size() ? k[v & 63] : '=';
  }
  return out;
}

template <typename T>
void put(std::string& out, T v, bool big_endian) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

/// How a test file stores its arrays.
struct Layout {
  std::string format = "ascii";  // ascii, binary, appended
  std::string encoding = "raw";  // appended: raw or base64
  bool compressed = false;
  bool uint64_header = false;
  bool big_endian = false;
};

/// Writes the test mesh (a square as a quad, a triangle and a 2-triangle strip over 6 points,
/// with normals) as .vtp in the given layout.
class VtpWriter {
 public:
  explicit VtpWriter(Layout l) : l_(std::move(l)) {}

  std::string file(const std::string& field_data = "") {
    const std::vector<float> points{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 2, 1, 0};
    std::vector<float> normals;
    for (int i = 0; i < 6; ++i) normals.insert(normals.end(), {0, 0, 1});
    std::string body = "<PolyData>" + field_data +
                       "<Piece NumberOfPoints=\"6\" NumberOfPolys=\"2\" NumberOfStrips=\"1\">"
                       "<PointData Normals=\"Normals\">" +
                       array("Float32", "Normals", 3, normals) + "</PointData><Points>" +
                       array("Float32", "", 3, points) + "</Points><Polys>" +
                       array<std::int64_t>("Int64", "connectivity", 1, {0, 1, 2, 3, 0, 1, 2}) +
                       array<std::int32_t>("Int32", "offsets", 1, {4, 7}) + "</Polys><Strips>" +
                       array<std::int64_t>("Int64", "connectivity", 1, {1, 4, 2, 5}) +
                       array<std::int64_t>("Int64", "offsets", 1, {4}) + "</Strips></Piece></PolyData>";
    std::string out = "<?xml version=\"1.0\"?>\n<!-- a comment -->\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"" +
                      std::string(l_.big_endian ? "BigEndian" : "LittleEndian") + "\" header_type=\"" +
                      (l_.uint64_header ? "UInt64" : "UInt32") + "\"" +
                      (l_.compressed ? " compressor=\"vtkZLibDataCompressor\"" : "") + ">\n" + body;
    if (l_.format == "appended") {
      out += "<AppendedData encoding=\"" + l_.encoding + "\">\n   _" + appended_ + "\n</AppendedData>";
    }
    return out + "</VTKFile>\n";
  }

  template <typename T>
  std::string array(const std::string& type, const std::string& name, int components, const std::vector<T>& v) {
    std::string head = "<DataArray type=\"" + type + "\"" + (name.empty() ? "" : " Name=\"" + name + "\"") +
                       " NumberOfComponents=\"" + std::to_string(components) + "\" format=\"" + l_.format + "\"";
    if (l_.format == "ascii") {
      std::string text;
      for (T x : v) text += std::to_string(x) + " ";
      return head + ">\n" + text + "\n</DataArray>";
    }
    std::string raw;
    for (T x : v) put(raw, x, l_.big_endian);
    const std::string block = encode(raw);
    if (l_.format == "binary") return head + ">" + block + "</DataArray>";
    head += " offset=\"" + std::to_string(appended_.size()) + "\"/>";
    appended_ += block;
    return head;
  }

 private:
  void header(std::string& out, std::uint64_t v) const {
    if (l_.uint64_header) {
      put(out, v, l_.big_endian);
    } else {
      put(out, static_cast<std::uint32_t>(v), l_.big_endian);
    }
  }
  /// [header][data] (compressed: one block per 8 bytes of data, to test several blocks).
  std::string encode(const std::string& raw) const {
    const bool text = l_.format == "binary" || l_.encoding == "base64";
    if (!l_.compressed) {
      std::string h;
      header(h, raw.size());
      return text ? base64(h + raw) : h + raw;
    }
    const std::size_t block = 8;
    const std::size_t blocks = (raw.size() + block - 1) / block;
    std::string h, data;
    header(h, blocks);
    header(h, block);
    header(h, raw.size() % block);
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::string part = raw.substr(b * block, block);
      uLongf size = compressBound(part.size());
      std::string z(size, '\0');
      compress(reinterpret_cast<Bytef*>(z.data()), &size, reinterpret_cast<const Bytef*>(part.data()), part.size());
      z.resize(size);
      header(h, z.size());
      data += z;
    }
    return text ? base64(h) + base64(data) : h + data;  // VTK encodes the two separately
  }

  Layout l_;
  std::string appended_;
};

void expect_test_mesh(const TriangleMesh& m) {
  ASSERT_EQ(m.num_vertices(), 6);
  ASSERT_EQ(m.num_faces(), 5);
  EXPECT_EQ(m.F.row(0), (Eigen::RowVector3i(0, 1, 2)));
  EXPECT_EQ(m.F.row(1), (Eigen::RowVector3i(0, 2, 3)));
  EXPECT_EQ(m.F.row(2), (Eigen::RowVector3i(0, 1, 2)));
  EXPECT_EQ(m.F.row(3), (Eigen::RowVector3i(1, 4, 2)));
  EXPECT_EQ(m.F.row(4), (Eigen::RowVector3i(2, 4, 5)));
  EXPECT_EQ(m.V(5, 0), 2.0);
  ASSERT_TRUE(m.has_normals());
  EXPECT_EQ(m.N(4, 2), 1.0);
}

TEST(ReadVtp, EveryDataLayoutReadsTheSameMesh) {
  std::vector<Layout> layouts;
  for (const char* format : {"ascii", "binary", "appended"})
    for (const char* encoding : {"raw", "base64"})
      for (bool compressed : {false, true})
        for (bool uint64 : {false, true})
          for (bool big : {false, true}) {
            if (std::string(format) != "appended" && std::string(encoding) == "base64") continue;
            if (std::string(format) == "ascii" && (compressed || uint64 || big)) continue;
            layouts.push_back({format, encoding, compressed, uint64, big});
          }
  ASSERT_EQ(layouts.size(), 1u + 8u + 16u);
  for (const Layout& l : layouts) {
    SCOPED_TRACE(l.format + " " + l.encoding + (l.compressed ? " zlib" : "") + (l.uint64_header ? " UInt64" : "") +
                 (l.big_endian ? " big" : ""));
    expect_test_mesh(read_vtp_from_memory(VtpWriter(l).file(), "m.vtp"));
  }
}

TEST(ReadVtp, SlicerSpaceFieldRasIsConvertedToLps) {
  // 3D Slicer's ascii .vtp: the SPACE string array as character codes ("RAS").
  const auto field = [](const char* codes) {
    return std::string("<FieldData><Array type=\"String\" Name=\"SPACE\" NumberOfTuples=\"1\" format=\"ascii\">") +
           codes + "</Array></FieldData>";
  };
  VtpWriter w({});
  const TriangleMesh ras = read_vtp_from_memory(w.file(field("82 65 83 0")), "r.vtp");
  const TriangleMesh lps = read_vtp_from_memory(VtpWriter({}).file(field("76 80 83 0")), "l.vtp");
  EXPECT_EQ(lps.V(2, 0), 1.0);
  EXPECT_EQ(ras.V(2, 0), -1.0);
  EXPECT_EQ(ras.V(2, 1), -1.0);
  EXPECT_EQ(ras.F, lps.F);
}

std::string problem(const std::string& bytes) {
  try {
    read_vtp_from_memory(bytes, "x.vtp");
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.problem();
  }
  ADD_FAILURE() << "no error";
  return "";
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

TEST(ReadVtp, MalformedFilesGiveOneLineErrors) {
  const std::string ascii = VtpWriter({}).file();
  EXPECT_EQ(problem(""), "empty file");
  EXPECT_NE(problem("solid x\nendsolid\n").find("not a VTK XML file"), std::string::npos);
  EXPECT_NE(problem(replace(ascii, "type=\"PolyData\"", "type=\"UnstructuredGrid\"")).find("not PolyData"), std::string::npos);
  EXPECT_NE(problem(replace(ascii, "type=\"PolyData\" version=\"1.0\"", "type=\"PolyData\" compressor=\"vtkLZ4DataCompressor\"")).find("is not supported"),
            std::string::npos);
  EXPECT_NE(problem(replace(ascii, "</Points>", "")).find("does not match"), std::string::npos);
  EXPECT_NE(problem(replace(ascii, "4 7", "4 3")).find("the cell offsets decrease"), std::string::npos);
  EXPECT_NE(problem(replace(ascii, "0 1 2 3 0 1 2", "0 1 2 3 0 1 9")).find("<Polys> cell 1 references point 9"),
            std::string::npos);
  EXPECT_NE(problem(replace(ascii, "NumberOfPoints=\"6\"", "NumberOfPoints=\"7\"")).find("<Points>: 18 values, expected 21"),
            std::string::npos);
  EXPECT_NE(problem(ascii.substr(0, ascii.size() / 2)).find("the file ends inside"), std::string::npos);

  // Compressed blocks announcing more than the array holds are refused before inflating.
  const std::string zipped = VtpWriter({"appended", "raw", true, false, false}).file();
  EXPECT_NE(problem(replace(zipped, "NumberOfPoints=\"6\"", "NumberOfPoints=\"600000\"")).find("expected 7200000"),
            std::string::npos);
  const std::size_t data = zipped.find('_', zipped.find("<AppendedData")) + 1;
  std::string corrupt = zipped;
  corrupt[data + 12 + 9 * 4 + 5] ^= 0x55;  // inside the first zlib block of the normals (9 blocks)
  EXPECT_NE(problem(corrupt).find("corrupt"), std::string::npos);
}

TEST(ReadVtp, ZlibBlocksAnnouncingMoreThanTheyCanHoldAreRefusedBeforeInflating) {
  // Found by fuzz_vtp: a connectivity array (size unknown until its offsets are read) whose
  // block table announces 939 MB in a 700-byte file was inflated into a 939 MB buffer.
  std::ifstream in(test::data_dir() / "fuzz" / "vtp" / "fuzz_zlib_blocks_announce_939mb.vtp", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(bytes.empty());
  EXPECT_NE(problem(bytes).find("<Polys> connectivity"), std::string::npos) << problem(bytes);
  // The same lie in an array of unknown size (a field-data string) is refused by the ratio bound.
  std::string blocks;
  for (std::uint32_t v : {1u, 939524153u, 939524153u, 16u}) put(blocks, v, false);
  blocks += std::string(16, 'x');
  const std::string field = "<VTKFile type=\"PolyData\" compressor=\"vtkZLibDataCompressor\"><PolyData><FieldData>"
                            "<Array type=\"String\" Name=\"SPACE\" format=\"appended\" offset=\"0\"/></FieldData>"
                            "</PolyData><AppendedData encoding=\"raw\">_" + blocks + "</AppendedData></VTKFile>";
  EXPECT_NE(problem(field).find("cannot hold the 939524153 bytes announced"), std::string::npos) << problem(field);
}

TEST(ReadVtp, EveryPrefixOfACompressedFileReadsOrFailsCleanly) {
  const std::string full = VtpWriter({"appended", "raw", true, true, false}).file();
  for (std::size_t n = 0; n < full.size(); ++n) {
    try {
      read_vtp_from_memory(std::string_view(full).substr(0, n), "p.vtp");
    } catch (const IoError&) {
    }
  }
  expect_test_mesh(read_vtp_from_memory(full, "p.vtp"));
}

}  // namespace
}  // namespace breastfit::io
