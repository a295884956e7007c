#include "breastfit/io/read_vtk.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/io/detail/file_bytes.h"
#include "breastfit/io/detail/slicer_space.h"
#include "breastfit/io/detail/text.h"
#include "breastfit/io/detail/vtk_cells.h"
#include "breastfit/io/detail/vtk_values.h"

namespace breastfit::io {
namespace {


using detail::VtkCellArray;
using detail::VtkCellKind;
using detail::VtkScalar;

std::string upper(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return out;
}

/// The tokens of one keyword line.
std::vector<std::string_view> tokens_of(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::string_view t = detail::next_token(line); !t.empty(); t = detail::next_token(line)) {
    out.push_back(t);
  }
  return out;
}

/// A scalar type named in the file, or a bit array (packed, no byte size), or a string array.
struct ArrayType {
  enum class Kind { Scalar, Bit, String };
  Kind kind = Kind::Scalar;
  VtkScalar scalar;
};

/// Walks the file: keyword lines, then each section's values (ASCII tokens or big-endian
/// binary).
class LegacyVtkReader {
 public:
  LegacyVtkReader(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  TriangleMesh read() {
    read_header();
    const auto dataset = next_line();
    const std::vector<std::string_view> t = dataset ? tokens_of(*dataset) : std::vector<std::string_view>{};
    if (t.size() != 2 || upper(t[0]) != "DATASET") {
      fail(dataset ? "expected 'DATASET <type>' after the header, found " + detail::quoted(*dataset)
                   : "no DATASET line after the header");
    }
    const std::string type = upper(t[1]);
    if (type != "POLYDATA" && type != "UNSTRUCTURED_GRID") {
      fail("DATASET " + detail::quoted(t[1]) +
           " is not a surface mesh (supported: POLYDATA, UNSTRUCTURED_GRID)");
    }
    grid_ = type == "UNSTRUCTURED_GRID";
    read_sections();
    return finish();
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw IoError(name_, problem); }

  // --- lines and tokens -------------------------------------------------------------------

  /// The rest of the current line (without CR/LF), advancing past its end.
  std::string_view raw_line() {
    const std::size_t end = std::min(bytes_.find('\n', pos_), bytes_.size());
    std::string_view line = bytes_.substr(pos_, end - pos_);
    pos_ = std::min(end + 1, bytes_.size());
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }

  /// The next non-blank line, or nothing at the end of the file.
  std::optional<std::string_view> next_line() {
    while (pos_ < bytes_.size()) {
      const std::string_view line = raw_line();
      std::string_view rest = line;
      if (!detail::next_token(rest).empty()) return line;
    }
    return std::nullopt;
  }

  /// The next line when its first token is `keyword` (case-insensitive); else nothing, and the
  /// position is unchanged.
  std::optional<std::string_view> line_if(std::string_view keyword) {
    const std::size_t saved = pos_;
    const auto line = next_line();
    if (line) {
      std::string_view rest = *line;
      if (upper(detail::next_token(rest)) == keyword) return line;
    }
    pos_ = saved;
    return std::nullopt;
  }

  /// ASCII data may start on its keyword line ("LINES 1 348 347" then the other 347 indices):
  /// moves back to just after the keyword line's first `used` tokens.
  void rewind_after(const std::vector<std::string_view>& t, std::size_t used) {
    if (binary_ || t.size() <= used || used == 0) return;
    pos_ = static_cast<std::size_t>(t[used - 1].data() + t[used - 1].size() - bytes_.data());
  }

  std::string_view next_value_token() {
    while (pos_ < bytes_.size() && (detail::is_blank(bytes_[pos_]) || bytes_[pos_] == '\n')) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && !detail::is_blank(bytes_[pos_]) && bytes_[pos_] != '\n') ++pos_;
    return bytes_.substr(start, pos_ - start);
  }

  void read_header() {
    const std::string_view first = raw_line();
    if (first.rfind("# vtk DataFile Version", 0) != 0) {
      fail(bytes_.empty() ? "empty file"
                          : "not a legacy VTK file (it does not start with '# vtk DataFile Version')");
    }
    if (pos_ >= bytes_.size()) fail("truncated header: no title line");
    title_ = raw_line();
    const auto format = next_line();
    const std::string f = format ? upper(tokens_of(*format).front()) : "";
    if (f == "ASCII") {
      binary_ = false;
    } else if (f == "BINARY") {
      binary_ = true;
    } else {
      fail(format ? "unknown format " + detail::quoted(*format) + " (expected ASCII or BINARY)"
                  : "truncated header: no ASCII/BINARY line");
    }
  }

  // --- values -------------------------------------------------------------------------------

  ArrayType array_type(std::string_view type_name, std::string_view section) const {
    if (const auto s = detail::legacy_vtk_scalar(type_name)) return {ArrayType::Kind::Scalar, *s};
    if (type_name == "bit") return {ArrayType::Kind::Bit, {}};
    if (type_name == "string" || type_name == "utf8_string") return {ArrayType::Kind::String, {}};
    fail(std::string(section) + ": unknown data type " + detail::quoted(type_name));
  }

  /// Fails unless `count` values of `bytes_each` bytes (binary) or tokens (ascii) can follow.
  void check_room(std::uint64_t count, std::size_t bytes_each, std::string_view section) const {
    const std::uint64_t left = bytes_.size() - pos_;
    const bool fits = binary_ ? count <= left / bytes_each : count <= left / 2 + 1;
    if (!fits) {
      fail(std::string(section) + ": " + std::to_string(count) +
           " values announced but only " + std::to_string(left) + " bytes of data follow");
    }
  }

  /// Reads `count` values (binary: big-endian `type`; ascii: tokens) as doubles or int64.
  template <typename T>
  void read_values(std::uint64_t count, VtkScalar type, std::string_view section, std::vector<T>& out) {
    constexpr bool integers = std::is_same_v<T, std::int64_t>;
    if (integers && type.kind == VtkScalar::Kind::Float) {
      fail(std::string(section) + ": point indices must have an integer type");
    }
    check_room(count, type.bytes, section);
    if (binary_) {
      if constexpr (integers) {
        detail::decode_vtk_integers(bytes_.data() + pos_, count, type, true, out);
      } else {
        detail::decode_vtk_doubles(bytes_.data() + pos_, count, type, true, out);
      }
      pos_ += count * type.bytes;
      return;
    }
    out.reserve(out.size() + count);
    for (std::uint64_t i = 0; i < count; ++i) {
      const std::string_view token = next_value_token();
      T v = 0;
      if (token.empty()) {
        fail(std::string(section) + ": the file ends after " + std::to_string(i) + " of " +
             std::to_string(count) + " values");
      }
      bool ok = false;
      if constexpr (integers) {
        ok = detail::parse_int64(token, v);
      } else {
        ok = detail::parse_double(token, v);
        // A float array's text is a float value: round as the binary encoding would store it.
        if (ok && type.kind == VtkScalar::Kind::Float && type.bytes == 4) v = static_cast<float>(v);
      }
      if (!ok) {
        fail(std::string(section) + (integers ? ": bad integer " : ": bad value ") + detail::quoted(token) +
             " (value " + std::to_string(i) + " of " + std::to_string(count) + ")");
      }
      out.push_back(v);
    }
  }

  /// Skips `count` values of an array of any type (strings: one per line in ascii files).
  void skip_values(std::uint64_t count, const ArrayType& type, std::string_view section) {
    if (type.kind == ArrayType::Kind::String) {
      if (binary_) fail(std::string(section) + ": string arrays in BINARY files are not supported");
      for (std::uint64_t i = 0; i < count; ++i) {
        if (!next_line()) fail(std::string(section) + ": the file ends inside a string array");
      }
      return;
    }
    if (binary_) {
      const std::uint64_t n = type.kind == ArrayType::Kind::Bit ? (count + 7) / 8 : count;
      const std::size_t each = type.kind == ArrayType::Kind::Bit ? 1 : type.scalar.bytes;
      check_room(n, each, section);
      pos_ += n * each;
      return;
    }
    check_room(count, 1, section);
    for (std::uint64_t i = 0; i < count; ++i) {
      if (next_value_token().empty()) {
        fail(std::string(section) + ": the file ends after " + std::to_string(i) + " of " +
             std::to_string(count) + " values");
      }
    }
  }

  /// VTK ≥ 8 may follow an array with `METADATA` lines ending at a blank line.
  void skip_metadata() {
    if (!line_if("METADATA")) return;
    while (pos_ < bytes_.size()) {
      std::string_view rest = raw_line();
      if (detail::next_token(rest).empty()) return;
    }
  }

  // --- sections -----------------------------------------------------------------------------

  std::uint64_t count_token(std::string_view token, std::string_view section) const {
    std::int64_t v = 0;
    if (!detail::parse_int64(token, v) || v < 0) {
      fail(std::string(section) + ": bad count " + detail::quoted(token));
    }
    if (v > (std::int64_t{1} << 48)) fail(std::string(section) + ": absurd count " + std::string(token));
    return static_cast<std::uint64_t>(v);
  }

  void expect_tokens(const std::vector<std::string_view>& t, std::size_t n,
                     std::string_view usage) const {
    if (t.size() < n) fail("bad line starting " + detail::quoted(t.empty() ? "" : t[0]) + " (expected '" +
                           std::string(usage) + "')");
  }

  void read_points(const std::vector<std::string_view>& t) {
    expect_tokens(t, 3, "POINTS n type");
    if (!points_.empty()) fail("two POINTS sections");
    const std::uint64_t n = count_token(t[1], "POINTS");
    if (n == 0) fail("the file has no points");
    const ArrayType type = array_type(t[2], "POINTS");
    if (type.kind != ArrayType::Kind::Scalar) fail("POINTS: coordinates must be numbers");
    rewind_after(t, 3);
    read_values(3 * n, type.scalar, "POINTS", points_);
    for (std::size_t i = 0; i < points_.size(); ++i) {
      if (!std::isfinite(points_[i])) {
        fail("point " + std::to_string(i / 3) + " has a non-finite coordinate (" +
             detail::format_double(points_[i]) + ")");
      }
    }
    skip_metadata();
  }

  /// A cell section: `KEY cells size` then the classic lists, or VTK ≥ 5.1's
  /// `KEY offsets connectivity` then OFFSETS and CONNECTIVITY arrays.
  VtkCellArray read_cells(const std::vector<std::string_view>& t) {
    const std::string section = upper(t[0]);
    expect_tokens(t, 3, section + " n size");
    const std::uint64_t first = count_token(t[1], section);
    const std::uint64_t second = count_token(t[2], section);
    rewind_after(t, 3);
    VtkCellArray cells;
    if (const auto offsets = line_if("OFFSETS")) {
      const std::vector<std::string_view> o = tokens_of(*offsets);
      expect_tokens(o, 2, "OFFSETS type");
      cells.offsets.clear();
      read_values(first, integer_type(o[1], section), section + " OFFSETS", cells.offsets);
      skip_metadata();
      const auto connectivity = line_if("CONNECTIVITY");
      if (!connectivity) fail(section + ": OFFSETS without a CONNECTIVITY array");
      const std::vector<std::string_view> c = tokens_of(*connectivity);
      expect_tokens(c, 2, "CONNECTIVITY type");
      read_values(second, integer_type(c[1], section), section + " CONNECTIVITY",
                    cells.connectivity);
      skip_metadata();
      if (cells.offsets.empty()) cells.offsets.push_back(0);
      detail::check_vtk_cell_array(cells, name_, section);
      return cells;
    }
    std::vector<std::int64_t> lists;
    read_values(second, VtkScalar{VtkScalar::Kind::Signed, 4}, section, lists);
    std::size_t at = 0;
    cells.offsets.reserve(std::min<std::uint64_t>(first, lists.size()) + 1);
    for (std::uint64_t i = 0; i < first; ++i) {
      if (at >= lists.size() || lists[at] < 0 ||
          static_cast<std::uint64_t>(lists[at]) > lists.size() - at - 1) {
        fail(section + ": cell " + std::to_string(i) + " of " + std::to_string(first) +
             " runs past the " + std::to_string(second) + " values announced");
      }
      cells.connectivity.insert(cells.connectivity.end(), lists.begin() + static_cast<std::ptrdiff_t>(at + 1),
                                lists.begin() + static_cast<std::ptrdiff_t>(at + 1 + lists[at]));
      cells.offsets.push_back(static_cast<std::int64_t>(cells.connectivity.size()));
      at += 1 + static_cast<std::size_t>(lists[at]);
    }
    if (at != lists.size()) {
      fail(section + ": " + std::to_string(first) + " cells use " + std::to_string(at) +
           " values but " + std::to_string(second) + " are announced");
    }
    skip_metadata();
    return cells;
  }

  VtkScalar integer_type(std::string_view type_name, const std::string& section) const {
    const ArrayType type = array_type(type_name, section);
    if (type.kind != ArrayType::Kind::Scalar || type.scalar.kind == VtkScalar::Kind::Float) {
      fail(section + ": point indices must have an integer type, not " + detail::quoted(type_name));
    }
    return type.scalar;
  }

  void read_cell_types(const std::vector<std::string_view>& t) {
    expect_tokens(t, 2, "CELL_TYPES n");
    const std::uint64_t n = count_token(t[1], "CELL_TYPES");
    rewind_after(t, 2);
    cell_types_.clear();
    read_values(n, VtkScalar{VtkScalar::Kind::Signed, 4}, "CELL_TYPES", cell_types_);
    skip_metadata();
  }

  /// FIELD name n: n arrays `name components tuples type` (or NULL_ARRAY) with their values.
  void skip_field(const std::vector<std::string_view>& t) {
    expect_tokens(t, 3, "FIELD name n");
    const std::uint64_t arrays = count_token(t[2], "FIELD");
    for (std::uint64_t a = 0; a < arrays; ++a) {
      const auto line = next_line();
      if (!line) fail("FIELD: the file ends before array " + std::to_string(a));
      const std::vector<std::string_view> f = tokens_of(*line);
      if (f.size() == 1 && f[0] == "NULL_ARRAY") continue;
      expect_tokens(f, 4, "name components tuples type");
      const std::string section = "FIELD array " + detail::quoted(f[0]);
      const std::uint64_t components = count_token(f[1], section);
      const std::uint64_t tuples = count_token(f[2], section);
      rewind_after(f, 4);
      skip_values(components * tuples, array_type(f[3], section), section);
      skip_metadata();
    }
  }

  /// One attribute of POINT_DATA / CELL_DATA with `n` tuples.
  void read_attribute(const std::vector<std::string_view>& t, std::uint64_t n, bool on_points) {
    const std::string key = upper(t[0]);
    const bool keep = on_points && n == points_.size() / 3;
    if (key == "FIELD") return skip_field(t);
    if (key == "LOOKUP_TABLE") {
      expect_tokens(t, 3, "LOOKUP_TABLE name size");
      const std::uint64_t size = count_token(t[2], key);
      rewind_after(t, 3);
      return skip_values(4 * size, binary_ ? ArrayType{ArrayType::Kind::Scalar, {VtkScalar::Kind::Unsigned, 1}}
                                           : ArrayType{ArrayType::Kind::Scalar, {VtkScalar::Kind::Float, 4}},
                         key);
    }
    if (key == "COLOR_SCALARS") {
      expect_tokens(t, 3, "COLOR_SCALARS name components");
      const std::uint64_t components = count_token(t[2], key);
      if (components == 0 || components > 4) fail(key + ": bad component count");
      rewind_after(t, 3);
      std::vector<double> values;
      const VtkScalar type = binary_ ? VtkScalar{VtkScalar::Kind::Unsigned, 1}
                                     : VtkScalar{VtkScalar::Kind::Float, 4};
      read_values(components * n, type, key, values);
      skip_metadata();
      if (keep && components >= 3 && data_.colors.empty()) {
        data_.colors.reserve(3 * n);
        for (std::uint64_t i = 0; i < n; ++i) {
          for (std::uint64_t k = 0; k < 3; ++k) {
            double v = values[i * components + k];
            if (!binary_) v *= 255.0;
            v = std::isfinite(v) ? std::clamp(std::round(v), 0.0, 255.0) : 0.0;
            data_.colors.push_back(static_cast<std::uint8_t>(v));
          }
        }
      }
      return;
    }
    std::uint64_t components = 1;
    std::string_view type_name;
    if (key == "SCALARS") {
      expect_tokens(t, 3, "SCALARS name type [components]");
      type_name = t[2];
      if (t.size() >= 4) components = count_token(t[3], key);
      rewind_after(t, 4);
      if (const auto table = line_if("LOOKUP_TABLE")) {
        rewind_after(tokens_of(*table), 2);
      }
    } else if (key == "TEXTURE_COORDINATES") {
      expect_tokens(t, 4, "TEXTURE_COORDINATES name dimension type");
      components = count_token(t[2], key);
      type_name = t[3];
      rewind_after(t, 4);
    } else if (key == "VECTORS" || key == "NORMALS" || key == "TENSORS" || key == "TENSORS6" ||
               key == "GLOBAL_IDS" || key == "PEDIGREE_IDS" || key == "EDGE_FLAGS") {
      expect_tokens(t, 3, key + " name type");
      type_name = t[2];
      rewind_after(t, 3);
      components = key == "VECTORS" || key == "NORMALS" ? 3
                   : key == "TENSORS"                   ? 9
                   : key == "TENSORS6"                  ? 6
                                                        : 1;
    } else {
      fail("unexpected keyword " + detail::quoted(t[0]) + " in " + (on_points ? "POINT_DATA" : "CELL_DATA"));
    }
    if (components > 16) fail(key + ": bad component count");
    const ArrayType type = array_type(type_name, key);
    const bool wanted = keep && type.kind == ArrayType::Kind::Scalar &&
                        ((key == "NORMALS" && data_.normals.empty()) ||
                         (key == "TEXTURE_COORDINATES" && components == 2 && data_.uv.empty()));
    if (!wanted) {
      skip_values(components * n, type, key);
    } else {
      read_values(components * n, type.scalar, key, key == "NORMALS" ? data_.normals : data_.uv);
    }
    skip_metadata();
  }

  void read_sections() {
    enum class Data { None, Points, Cells } data = Data::None;
    std::uint64_t data_count = 0;
    while (const auto line = next_line()) {
      const std::vector<std::string_view> t = tokens_of(*line);
      const std::string key = upper(t[0]);
      if (key == "POINTS") {
        read_points(t);
      } else if (key == "POLYGONS" || key == "TRIANGLE_STRIPS" || key == "VERTICES" ||
                 key == "LINES" || (grid_ && key == "CELLS")) {
        if (points_.empty()) fail(key + " before POINTS");
        VtkCellArray cells = read_cells(t);
        if (key == "POLYGONS") polygons_.push_back(std::move(cells));
        if (key == "TRIANGLE_STRIPS") strips_.push_back(std::move(cells));
        if (key == "CELLS") grid_cells_ = std::move(cells);
      } else if (grid_ && key == "CELL_TYPES") {
        read_cell_types(t);
      } else if (key == "POINT_DATA" || key == "CELL_DATA") {
        expect_tokens(t, 2, key + " n");
        data = key == "POINT_DATA" ? Data::Points : Data::Cells;
        data_count = count_token(t[1], key);
      } else if (key == "METADATA") {
        // a METADATA block not right after an array: skipped the same way
        while (pos_ < bytes_.size()) {
          std::string_view rest = raw_line();
          if (detail::next_token(rest).empty()) break;
        }
      } else if (key == "FIELD" && data == Data::None) {
        skip_field(t);
      } else if (data != Data::None) {
        read_attribute(t, data_count, data == Data::Points);
      } else {
        fail("unexpected keyword " + detail::quoted(t[0]));
      }
    }
  }

  TriangleMesh finish() {
    if (points_.empty()) fail("the file has no POINTS");
    detail::VtkTriangles triangles(name_, points_);
    for (const VtkCellArray& c : polygons_) triangles.add_all(VtkCellKind::Polygon, c, "POLYGONS");
    for (const VtkCellArray& c : strips_) triangles.add_all(VtkCellKind::TriangleStrip, c, "TRIANGLE_STRIPS");
    if (grid_) {
      if (cell_types_.size() != grid_cells_.size()) {
        fail("CELL_TYPES lists " + std::to_string(cell_types_.size()) + " types for " +
             std::to_string(grid_cells_.size()) + " CELLS");
      }
      std::size_t volume = 0;
      for (std::size_t i = 0; i < grid_cells_.size(); ++i) {
        const VtkCellKind kind = detail::vtk_cell_kind(cell_types_[i]);
        if (kind == VtkCellKind::Other && cell_types_[i] >= 10) ++volume;
        const auto begin = static_cast<std::size_t>(grid_cells_.offsets[i]);
        const auto end = static_cast<std::size_t>(grid_cells_.offsets[i + 1]);
        triangles.add(kind, grid_cells_.connectivity.data() + begin, end - begin, "CELLS", i);
      }
      if (triangles.triangles().empty() && volume > 0) {
        fail("the UNSTRUCTURED_GRID holds " + std::to_string(volume) +
             " volume cells and no surface cells (triangles, quads, polygons, strips): extract "
             "its surface first (ParaView: Extract Surface) and save that");
      }
    }
    return detail::vtk_mesh(points_, triangles.triangles(), data_, detail::slicer_space_in_header(title_));
  }

  std::string_view bytes_;
  const std::string& name_;
  std::size_t pos_ = 0;
  bool binary_ = false;
  bool grid_ = false;
  std::string_view title_;
  std::vector<double> points_;
  detail::VtkPointData data_;
  std::vector<VtkCellArray> polygons_, strips_;
  VtkCellArray grid_cells_;
  std::vector<std::int64_t> cell_types_;
};

}  // namespace

TriangleMesh read_vtk_from_memory(std::string_view bytes, const std::string& name) {
  return LegacyVtkReader(bytes, name).read();
}

TriangleMesh read_vtk(const std::filesystem::path& path) {
  return read_vtk_from_memory(detail::read_file_bytes(path), path.string());
}

}  // namespace breastfit::io
