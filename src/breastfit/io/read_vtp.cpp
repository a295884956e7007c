#include "breastfit/io/read_vtp.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/io/detail/base64.h"
#include "breastfit/io/detail/file_bytes.h"
#include "breastfit/io/detail/slicer_space.h"
#include "breastfit/io/detail/text.h"
#include "breastfit/io/detail/vtk_cells.h"
#include "breastfit/io/detail/vtk_values.h"
#include "breastfit/io/detail/xml_elements.h"
#include "breastfit/io/detail/zlib_block.h"

namespace breastfit::io {
namespace {


using detail::VtkCellArray;
using detail::VtkCellKind;
using detail::VtkScalar;
using detail::XmlElement;

/// Raw bytes read in sequence (appended raw data).
class RawReader {
 public:
  explicit RawReader(std::string_view bytes) : bytes_(bytes) {}
  bool read(std::size_t count, std::string& out) {
    if (count > bytes_.size() - pos_) return false;
    out.append(bytes_.substr(pos_, count));
    pos_ += count;
    return true;
  }

 private:
  std::string_view bytes_;
  std::size_t pos_ = 0;
};

/// Arrays above this size (after inflating) are refused: far beyond any scan.
constexpr std::uint64_t kMaxArrayBytes = std::uint64_t{1} << 32;

class VtpReader {
 public:
  VtpReader(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  TriangleMesh read() {
    if (bytes_.empty()) fail("empty file");
    if (bytes_.find("<VTKFile") == std::string_view::npos) {
      fail("not a VTK XML file (no '<VTKFile' element)");
    }
    doc_ = detail::read_xml_elements(bytes_, name_);
    const XmlElement& root = doc_.elements.front();
    if (root.name != "VTKFile") fail("the root element is <" + detail::quoted(root.name) + ">, not '<VTKFile>'");
    read_file_attributes(root);
    const XmlElement* poly = child(root, "PolyData");
    if (poly == nullptr) fail("no <PolyData> element");
    if (doc_.appended_at != std::string_view::npos) locate_appended();
    for (std::size_t c : poly->children) {
      const XmlElement& e = doc_.elements[c];
      if (e.name == "FieldData") read_field_data(e);
      if (e.name == "Piece") read_piece(e);
    }
    return finish();
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw IoError(name_, problem); }

  const XmlElement* child(const XmlElement& parent, std::string_view tag) const {
    for (std::size_t c : parent.children) {
      if (doc_.elements[c].name == tag) return &doc_.elements[c];
    }
    return nullptr;
  }

  /// The DataArray (or, in field data, Array) child of `parent` whose Name is `array_name` (or
  /// the first when empty).
  const XmlElement* data_array(const XmlElement& parent, std::string_view array_name) const {
    for (std::size_t c : parent.children) {
      const XmlElement& e = doc_.elements[c];
      if (e.name != "DataArray" && e.name != "Array") continue;
      const std::string* n = e.attribute("Name");
      if (array_name.empty() || (n != nullptr && *n == array_name)) return &e;
    }
    return nullptr;
  }

  std::string attr_or(const XmlElement& e, std::string_view key, std::string_view fallback) const {
    const std::string* v = e.attribute(key);
    return v != nullptr ? *v : std::string(fallback);
  }

  std::uint64_t count_attr(const XmlElement& e, std::string_view key, std::uint64_t fallback) const {
    const std::string* v = e.attribute(key);
    if (v == nullptr) return fallback;
    std::int64_t n = 0;
    if (!detail::parse_int64(*v, n) || n < 0 || n > (std::int64_t{1} << 40)) {
      fail("<" + e.name + "> has a bad " + std::string(key) + " " + detail::quoted(*v));
    }
    return static_cast<std::uint64_t>(n);
  }

  void read_file_attributes(const XmlElement& root) {
    const std::string type = attr_or(root, "type", "");
    if (type != "PolyData") {
      fail("a VTK XML " + detail::quoted(type) + " file, not PolyData" +
           (type == "vtkMultiBlockDataSet" ? " (a multiblock index: open the .vtp files it lists)"
            : type == "UnstructuredGrid"   ? " (save the surface as .vtp or .vtk)"
                                           : ""));
    }
    const std::string order = attr_or(root, "byte_order", "LittleEndian");
    if (order != "LittleEndian" && order != "BigEndian") fail("unknown byte_order " + detail::quoted(order));
    big_endian_ = order == "BigEndian";
    const std::string header = attr_or(root, "header_type", "UInt32");
    if (header != "UInt32" && header != "UInt64") fail("unknown header_type " + detail::quoted(header));
    header_bytes_ = header == "UInt64" ? 8 : 4;
    const std::string compressor = attr_or(root, "compressor", "");
    if (compressor == "vtkZLibDataCompressor") {
      compressed_ = true;
    } else if (!compressor.empty()) {
      fail("data compressed with " + detail::quoted(compressor) +
           " is not supported (zlib or none): re-save the file with zlib compression or none");
    }
  }

  void locate_appended() {
    const XmlElement& appended = doc_.elements.back();
    const std::string encoding = attr_or(appended, "encoding", "raw");
    if (encoding != "raw" && encoding != "base64") fail("unknown AppendedData encoding " + detail::quoted(encoding));
    appended_base64_ = encoding == "base64";
    const std::size_t underscore = bytes_.find('_', doc_.appended_at);
    if (underscore == std::string_view::npos) fail("<AppendedData> has no '_' marking its start");
    appended_ = bytes_.substr(underscore + 1);
  }

  // --- arrays -------------------------------------------------------------------------------

  VtkScalar scalar_of(const XmlElement& a, const std::string& section) const {
    const std::string type = attr_or(a, "type", "");
    const auto s = detail::xml_vtk_scalar(type);
    if (!s) fail(section + ": unsupported DataArray type " + detail::quoted(type));
    return *s;
  }

  std::uint64_t header_value(const std::string& header, std::size_t index) const {
    std::vector<std::int64_t> v;
    detail::decode_vtk_integers(header.data() + index * header_bytes_, 1,
                                VtkScalar{VtkScalar::Kind::Unsigned, header_bytes_}, big_endian_, v);
    return static_cast<std::uint64_t>(v.front());
  }

  /// The array's bytes from a binary source: [size][data] or, compressed, [blocks, block size,
  /// last block size, compressed sizes…][blocks]. `expected` bytes unless nothing is expected.
  template <typename Source>
  std::string binary_bytes(Source& source, std::optional<std::uint64_t> expected,
                           const std::string& section) const {
    std::string header;
    const auto truncated = [&] { fail(section + ": the data ends early (truncated or corrupt)"); };
    if (!compressed_) {
      if (!source.read(header_bytes_, header)) truncated();
      const std::uint64_t size = header_value(header, 0);
      if (expected && size != *expected) {
        fail(section + ": the data holds " + std::to_string(size) + " bytes, expected " +
             std::to_string(*expected));
      }
      if (size > kMaxArrayBytes || size > bytes_.size() * 2) fail(section + ": absurd data size");
      std::string data;
      if (!source.read(static_cast<std::size_t>(size), data)) truncated();
      return data;
    }
    if (!source.read(3 * header_bytes_, header)) truncated();
    const std::uint64_t blocks = header_value(header, 0);
    const std::uint64_t block_size = header_value(header, 1);
    const std::uint64_t last_size = header_value(header, 2);
    if (blocks > bytes_.size() / header_bytes_) fail(section + ": absurd compressed block count");
    std::uint64_t total = 0;
    if (blocks > 0) {
      total = (blocks - 1) * block_size + (last_size == 0 ? block_size : last_size);
      if (block_size > kMaxArrayBytes || last_size > block_size) fail(section + ": bad compressed block sizes");
    }
    if (expected && total != *expected) {
      fail(section + ": the compressed data holds " + std::to_string(total) + " bytes, expected " +
           std::to_string(*expected));
    }
    if (total > kMaxArrayBytes) fail(section + ": absurd data size");
    if (!source.read(static_cast<std::size_t>(blocks * header_bytes_), header)) truncated();
    // Deflate expands at most ~1032:1: a larger total is a lie, refused before allocating.
    std::uint64_t compressed_total = 0;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      compressed_total += std::min<std::uint64_t>(header_value(header, static_cast<std::size_t>(3 + b)), bytes_.size());
    }
    if (total > 1032 * compressed_total + 1024) {
      fail(section + ": the compressed blocks (" + std::to_string(compressed_total) + " bytes) cannot hold the " +
           std::to_string(total) + " bytes announced");
    }
    std::string data;
    std::string block;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const std::uint64_t compressed_size = header_value(header, static_cast<std::size_t>(3 + b));
      if (compressed_size > bytes_.size()) truncated();
      block.clear();
      if (!source.read(static_cast<std::size_t>(compressed_size), block)) truncated();
      const std::uint64_t size = b + 1 == blocks && last_size != 0 ? last_size : block_size;
      if (!detail::inflate_zlib_block(block, static_cast<std::size_t>(size), data)) {
        fail(section + ": compressed block " + std::to_string(b) + " does not inflate (corrupt zlib data)");
      }
    }
    return data;
  }

  /// The bytes of a binary or appended array.
  std::string array_bytes(const XmlElement& a, std::optional<std::uint64_t> expected,
                          const std::string& section) const {
    const std::string format = attr_or(a, "format", "ascii");
    if (format == "binary") {
      detail::Base64Reader source(a.text);
      return binary_bytes(source, expected, section);
    }
    if (format != "appended") fail(section + ": unknown DataArray format " + detail::quoted(format));
    if (appended_.data() == nullptr) fail(section + ": an appended array but no <AppendedData>");
    const std::uint64_t offset = count_attr(a, "offset", 0);
    if (offset > appended_.size()) fail(section + ": offset " + std::to_string(offset) + " is past the appended data");
    if (appended_base64_) {
      detail::Base64Reader source(appended_.substr(static_cast<std::size_t>(offset)));
      return binary_bytes(source, expected, section);
    }
    RawReader source(appended_.substr(static_cast<std::size_t>(offset)));
    return binary_bytes(source, expected, section);
  }

  /// The array's `count` values as doubles.
  std::vector<double> doubles(const XmlElement& a, std::uint64_t count, const std::string& section) const {
    const VtkScalar type = scalar_of(a, section);
    std::vector<double> out;
    if (attr_or(a, "format", "ascii") == "ascii") {
      std::string_view text = a.text;
      out.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(count, text.size() / 2 + 1)));
      for (std::string_view t = next_token(text); !t.empty(); t = next_token(text)) {
        double v = 0;
        if (!detail::parse_double(t, v)) fail(section + ": bad value " + detail::quoted(t));
        if (type.kind == VtkScalar::Kind::Float && type.bytes == 4) v = static_cast<float>(v);  // as stored
        if (out.size() == count) fail(section + ": more than the " + std::to_string(count) + " values expected");
        out.push_back(v);
      }
      if (out.size() != count) {
        fail(section + ": " + std::to_string(out.size()) + " values, expected " + std::to_string(count));
      }
      return out;
    }
    if (count > kMaxArrayBytes / type.bytes) fail(section + ": absurd value count");
    const std::string bytes = array_bytes(a, count * type.bytes, section);
    detail::decode_vtk_doubles(bytes.data(), count, type, big_endian_, out);
    return out;
  }

  /// The array's `count` integer values (count unknown: `count` is nothing for ascii arrays, or
  /// read from the binary header).
  std::vector<std::int64_t> integers(const XmlElement& a, std::optional<std::uint64_t> count,
                                     const std::string& section) const {
    const VtkScalar type = scalar_of(a, section);
    if (type.kind == VtkScalar::Kind::Float) fail(section + ": point indices must have an integer type");
    std::vector<std::int64_t> out;
    if (attr_or(a, "format", "ascii") == "ascii") {
      std::string_view text = a.text;
      for (std::string_view t = next_token(text); !t.empty(); t = next_token(text)) {
        std::int64_t v = 0;
        if (!detail::parse_int64(t, v)) fail(section + ": bad integer " + detail::quoted(t));
        out.push_back(v);
      }
      if (count && out.size() != *count) {
        fail(section + ": " + std::to_string(out.size()) + " values, expected " + std::to_string(*count));
      }
      return out;
    }
    if (count && *count > kMaxArrayBytes / type.bytes) fail(section + ": absurd value count");
    const std::string bytes =
        array_bytes(a, count ? std::optional<std::uint64_t>(*count * type.bytes) : std::nullopt, section);
    if (bytes.size() % type.bytes != 0) fail(section + ": the data is not a whole number of values");
    detail::decode_vtk_integers(bytes.data(), bytes.size() / type.bytes, type, big_endian_, out);
    return out;
  }

  static std::string_view next_token(std::string_view& text) {
    std::size_t i = 0;
    while (i < text.size() && (detail::is_blank(text[i]) || text[i] == '\n')) ++i;
    std::size_t j = i;
    while (j < text.size() && !detail::is_blank(text[j]) && text[j] != '\n') ++j;
    const std::string_view t = text.substr(i, j - i);
    text.remove_prefix(j);
    return t;
  }

  // --- elements -----------------------------------------------------------------------------

  /// 3D Slicer's `SPACE` string array (ascii: character codes; binary: the bytes).
  void read_field_data(const XmlElement& field) {
    const XmlElement* a = data_array(field, "SPACE");
    if (a == nullptr || attr_or(*a, "type", "") != "String") return;
    std::string value;
    if (attr_or(*a, "format", "ascii") == "ascii") {
      std::string_view text = a->text;
      for (std::string_view t = next_token(text); !t.empty(); t = next_token(text)) {
        std::int64_t c = 0;
        if (detail::parse_int64(t, c) && c > 0 && c < 128) value.push_back(static_cast<char>(c));
      }
    } else {
      value = array_bytes(*a, std::nullopt, "FieldData SPACE");
    }
    space_ = detail::slicer_space_in_value(value);
  }

  VtkCellArray read_cell_array(const XmlElement& piece, std::string_view tag, std::uint64_t cells,
                               std::int64_t base) const {
    VtkCellArray out;
    const XmlElement* e = child(piece, tag);
    if (cells == 0) return out;
    const std::string section = "<" + std::string(tag) + ">";
    if (e == nullptr) fail("the piece announces " + std::to_string(cells) + " cells but has no " + section);
    const XmlElement* offsets = data_array(*e, "offsets");
    const XmlElement* connectivity = data_array(*e, "connectivity");
    if (offsets == nullptr || connectivity == nullptr) fail(section + " needs 'offsets' and 'connectivity' arrays");
    const std::vector<std::int64_t> ends = integers(*offsets, cells, section + " offsets");
    out.offsets.insert(out.offsets.end(), ends.begin(), ends.end());
    // The offsets bound the connectivity: checked before it is read.
    for (std::size_t i = 0; i < ends.size(); ++i) {
      if (ends[i] < (i == 0 ? 0 : ends[i - 1])) fail(section + ": the cell offsets decrease at cell " + std::to_string(i));
    }
    out.connectivity = integers(*connectivity, static_cast<std::uint64_t>(ends.back()), section + " connectivity");
    detail::check_vtk_cell_array(out, name_, section);
    for (std::int64_t& id : out.connectivity) {
      if (id >= 0 && id < std::numeric_limits<std::int64_t>::max() - base) id += base;
    }
    return out;
  }

  void read_piece(const XmlElement& piece) {
    const std::uint64_t n = count_attr(piece, "NumberOfPoints", 0);
    const auto base = static_cast<std::int64_t>(points_.size() / 3);
    ++pieces_;
    if (n > 0) {
      const XmlElement* pts = child(piece, "Points");
      const XmlElement* a = pts ? data_array(*pts, "") : nullptr;
      if (a == nullptr) fail("a piece with " + std::to_string(n) + " points has no <Points> DataArray");
      if (count_attr(*a, "NumberOfComponents", 1) != 3) fail("<Points> must have 3 components");
      const std::vector<double> p = doubles(*a, 3 * n, "<Points>");
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (!std::isfinite(p[i])) {
          fail("point " + std::to_string(base + static_cast<std::int64_t>(i / 3)) +
               " has a non-finite coordinate (" + detail::format_double(p[i]) + ")");
        }
      }
      points_.insert(points_.end(), p.begin(), p.end());
      read_point_data(piece, n);
    }
    polys_.push_back(read_cell_array(piece, "Polys", count_attr(piece, "NumberOfPolys", 0), base));
    strips_.push_back(read_cell_array(piece, "Strips", count_attr(piece, "NumberOfStrips", 0), base));
  }

  /// Active normals, 2D texture coordinates and UInt8 colour scalars of a piece with n points.
  void read_point_data(const XmlElement& piece, std::uint64_t n) {
    const XmlElement* pd = child(piece, "PointData");
    const auto active = [&](std::string_view role, std::uint64_t comps) -> const XmlElement* {
      const std::string* arr = pd ? pd->attribute(role) : nullptr;
      const XmlElement* a = arr ? data_array(*pd, *arr) : nullptr;
      if (a == nullptr || count_attr(*a, "NumberOfComponents", 1) != comps) return nullptr;
      return a;
    };
    const XmlElement* normals = active("Normals", 3);
    if (normals != nullptr) {
      const std::vector<double> v = doubles(*normals, 3 * n, "normals");
      data_.normals.insert(data_.normals.end(), v.begin(), v.end());
    }
    normals_ok_ = normals_ok_ && normals != nullptr;
    const XmlElement* uv = active("TCoords", 2);
    if (uv != nullptr) {
      const std::vector<double> v = doubles(*uv, 2 * n, "texture coordinates");
      data_.uv.insert(data_.uv.end(), v.begin(), v.end());
    }
    uv_ok_ = uv_ok_ && uv != nullptr;
    const XmlElement* colors = active("Scalars", 3);
    if (colors == nullptr) colors = active("Scalars", 4);
    if (colors != nullptr && attr_or(*colors, "type", "") == "UInt8") {
      const std::uint64_t comps = count_attr(*colors, "NumberOfComponents", 1);
      const std::vector<double> v = doubles(*colors, comps * n, "colours");
      for (std::uint64_t i = 0; i < n; ++i) {
        for (std::uint64_t k = 0; k < 3; ++k) {
          const double c = v[i * comps + k];  // ascii text may hold anything
          data_.colors.push_back(static_cast<std::uint8_t>(std::isfinite(c) ? std::clamp(c, 0.0, 255.0) : 0.0));
        }
      }
    } else {
      colors_ok_ = false;
    }
  }

  TriangleMesh finish() {
    if (pieces_ == 0) fail("no <Piece> in <PolyData>");
    if (points_.empty()) fail("the file has no points");
    detail::VtkTriangles triangles(name_, points_);
    for (const VtkCellArray& c : polys_) triangles.add_all(VtkCellKind::Polygon, c, "<Polys>");
    for (const VtkCellArray& c : strips_) triangles.add_all(VtkCellKind::TriangleStrip, c, "<Strips>");
    if (!normals_ok_) data_.normals.clear();
    if (!uv_ok_) data_.uv.clear();
    if (!colors_ok_) data_.colors.clear();
    return detail::vtk_mesh(points_, triangles.triangles(), data_, space_);
  }

  std::string_view bytes_;
  const std::string& name_;
  detail::XmlDocument doc_;
  bool big_endian_ = false;
  std::size_t header_bytes_ = 4;
  bool compressed_ = false;
  bool appended_base64_ = false;
  std::string_view appended_;
  detail::SlicerSpace space_ = detail::SlicerSpace::Unstated;
  std::size_t pieces_ = 0;
  std::vector<double> points_;
  detail::VtkPointData data_;
  bool normals_ok_ = true, uv_ok_ = true, colors_ok_ = true;
  std::vector<VtkCellArray> polys_, strips_;
};

}  // namespace

TriangleMesh read_vtp_from_memory(std::string_view bytes, const std::string& name) {
  return VtpReader(bytes, name).read();
}

TriangleMesh read_vtp(const std::filesystem::path& path) {
  return read_vtp_from_memory(detail::read_file_bytes(path), path.string());
}

}  // namespace breastfit::io
