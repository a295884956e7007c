#include "breastfit/io/read_ply.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/io/detail/mapped_file.h"
#include "breastfit/io/detail/mesh_arrays.h"
#include "breastfit/io/detail/polygon_triangulation.h"
#include "breastfit/io/detail/text.h"
#include "breastfit/mesh/index_triangulation.h"

namespace breastfit::io {
namespace {

using detail::quoted;

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyFormat { Ascii, BinaryLittle, BinaryBig };

struct PlyProperty {
  std::string name;
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;  // lists only
  PlyType type = PlyType::Float32;      // value type (of the list entries for lists)
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;  // first byte after the end_header line
  std::uint64_t lines = 0;      // number of header lines (ascii data line numbers follow)
};

std::optional<PlyType> parse_type(std::string_view s) {
  if (s == "char" || s == "int8") return PlyType::Int8;
  if (s == "uchar" || s == "uint8") return PlyType::UInt8;
  if (s == "short" || s == "int16") return PlyType::Int16;
  if (s == "ushort" || s == "uint16") return PlyType::UInt16;
  if (s == "int" || s == "int32") return PlyType::Int32;
  if (s == "uint" || s == "uint32") return PlyType::UInt32;
  if (s == "float" || s == "float32") return PlyType::Float32;
  if (s == "double" || s == "float64") return PlyType::Float64;
  return std::nullopt;
}

std::size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 1;
}

bool is_integer_type(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

/// Range check for integer-typed values read from ascii text.
bool fits_type(PlyType t, double v) {
  if (!is_integer_type(t)) return true;
  if (!(v == std::floor(v))) return false;  // also rejects NaN and inf
  switch (t) {
    case PlyType::Int8:
      return v >= -128 && v <= 127;
    case PlyType::UInt8:
      return v >= 0 && v <= 255;
    case PlyType::Int16:
      return v >= -32768 && v <= 32767;
    case PlyType::UInt16:
      return v >= 0 && v <= 65535;
    case PlyType::Int32:
      return v >= -2147483648.0 && v <= 2147483647.0;
    case PlyType::UInt32:
      return v >= 0 && v <= 4294967295.0;
    default:
      return true;
  }
}

std::string plural(std::uint64_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// ---------------------------------------------------------------------------------------------
// Header

PlyHeader parse_header(std::string_view bytes, const std::string& name) {
  if (bytes.empty()) throw IoError(name, "empty file");
  PlyHeader header;
  std::size_t pos = 0;
  bool has_format = false;
  bool first = true;
  while (true) {
    const std::size_t nl = bytes.find('\n', pos);
    if (nl == std::string_view::npos) {
      if (first && bytes.substr(0, 3) != "ply") {
        throw IoError(name, "not a PLY file (it does not start with 'ply')");
      }
      throw IoError(name, "truncated header: no 'end_header' line");
    }
    std::string_view line = bytes.substr(pos, nl - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = nl + 1;
    ++header.lines;
    const std::string at = "header line " + std::to_string(header.lines) + ": ";
    if (first) {
      if (line != "ply") throw IoError(name, "not a PLY file (it does not start with 'ply')");
      first = false;
      continue;
    }
    std::string_view rest = line;
    const std::string_view keyword = detail::next_token(rest);
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") break;
    if (keyword == "format") {
      const std::string_view kind = detail::next_token(rest);
      if (kind == "ascii") {
        header.format = PlyFormat::Ascii;
      } else if (kind == "binary_little_endian") {
        header.format = PlyFormat::BinaryLittle;
      } else if (kind == "binary_big_endian") {
        header.format = PlyFormat::BinaryBig;
      } else {
        throw IoError(name, at + "unknown format " + quoted(kind));
      }
      has_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      element.name = std::string(detail::next_token(rest));
      const std::string_view count = detail::next_token(rest);
      std::int64_t n = 0;
      if (element.name.empty() || !detail::parse_int64(count, n) || n < 0) {
        throw IoError(name,
                      at + "bad element line (expected 'element <name> <count>', count >= 0)");
      }
      element.count = static_cast<std::uint64_t>(n);
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) throw IoError(name, at + "property before any element");
      PlyProperty property;
      std::string_view type = detail::next_token(rest);
      if (type == "list") {
        property.is_list = true;
        const std::string_view count_type = detail::next_token(rest);
        const auto ct = parse_type(count_type);
        if (!ct) throw IoError(name, at + "unknown list count type " + quoted(count_type));
        if (!is_integer_type(*ct)) {
          throw IoError(name,
                        at + "list count type " + quoted(count_type) + " is not an integer type");
        }
        property.count_type = *ct;
        type = detail::next_token(rest);
      }
      const auto t = parse_type(type);
      if (!t) throw IoError(name, at + "unknown property type " + quoted(type));
      property.type = *t;
      property.name = std::string(detail::next_token(rest));
      if (property.name.empty()) throw IoError(name, at + "property without a name");
      header.elements.back().properties.push_back(std::move(property));
    } else {
      throw IoError(name, at + "unexpected keyword " + quoted(keyword));
    }
  }
  if (!has_format) throw IoError(name, "header has no 'format' line");
  header.data_offset = pos;
  return header;
}

/// Minimal number of bytes (binary) or characters (ascii) one instance of an element occupies.
std::uint64_t min_element_size(const PlyElement& element, PlyFormat format) {
  std::uint64_t size = 0;
  for (const PlyProperty& p : element.properties) {
    if (format == PlyFormat::Ascii) {
      size += 2;  // at least one character and one separator
    } else {
      size += type_size(p.is_list ? p.count_type : p.type);
    }
  }
  return size;
}

/// Rejects headers announcing more elements than the data can possibly hold, before allocating.
void check_counts_against_size(const PlyHeader& header, std::uint64_t data_size,
                               const std::string& name) {
  std::uint64_t remaining = data_size + (header.format == PlyFormat::Ascii ? 1 : 0);
  for (const PlyElement& element : header.elements) {
    const std::uint64_t per = min_element_size(element, header.format);
    if (per == 0 || element.count == 0) continue;
    if (element.count > remaining / per) {
      throw IoError(name, "header announces " + std::to_string(element.count) + " '" +
                              element.name + "' elements (at least " + std::to_string(per) +
                              (header.format == PlyFormat::Ascii ? " characters" : " bytes") +
                              " each) but only " + std::to_string(data_size) +
                              " bytes of data follow the header");
    }
    remaining -= element.count * per;
  }
}

// ---------------------------------------------------------------------------------------------
// Data sources: the same element readers run over ascii tokens or binary bytes.

enum class Status { Ok, End, Bad };

template <typename T>
double load_as(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return static_cast<double>(v);
}

/// Reads one scalar of type t (native byte order) at p.
inline double load_scalar(const unsigned char* p, PlyType t) {
  switch (t) {
    case PlyType::Int8: return load_as<std::int8_t>(p);
    case PlyType::UInt8: return load_as<std::uint8_t>(p);
    case PlyType::Int16: return load_as<std::int16_t>(p);
    case PlyType::UInt16: return load_as<std::uint16_t>(p);
    case PlyType::Int32: return load_as<std::int32_t>(p);
    case PlyType::UInt32: return load_as<std::uint32_t>(p);
    case PlyType::Float32: return load_as<float>(p);
    case PlyType::Float64: return load_as<double>(p);
  }
  return 0.0;
}

class BinarySource {
 public:
  BinarySource(std::string_view data, bool big_endian)
      : p_(reinterpret_cast<const unsigned char*>(data.data())),
        end_(p_ + data.size()),
        swap_(big_endian != (std::endian::native == std::endian::big)) {}

  Status read(PlyType t, double& out) {
    const std::size_t n = type_size(t);
    if (static_cast<std::size_t>(end_ - p_) < n) return Status::End;
    unsigned char b[8];
    std::memcpy(b, p_, n);
    if (swap_) std::reverse(b, b + n);
    p_ += n;
    out = load_scalar(b, t);
    return Status::Ok;
  }

  Status skip(PlyType t, std::uint64_t count) {
    const std::size_t n = type_size(t);
    if (count > static_cast<std::uint64_t>(end_ - p_) / n) return Status::End;
    p_ += count * n;
    return Status::Ok;
  }

  /// Upper bound on how many values of type t can still follow.
  std::uint64_t capacity(PlyType t) const {
    return static_cast<std::uint64_t>(end_ - p_) / type_size(t);
  }

  std::string where() const { return ""; }
  std::string_view last_token() const { return {}; }

 private:
  const unsigned char* p_;
  const unsigned char* end_;
  bool swap_;
};

class AsciiSource {
 public:
  AsciiSource(std::string_view data, std::uint64_t first_line) : data_(data), line_(first_line) {}

  Status read(PlyType t, double& out) {
    token_ = next();
    if (token_.empty()) return Status::End;
    if (!detail::parse_double(token_, out)) return Status::Bad;
    if (!fits_type(t, out)) return Status::Bad;
    if (t == PlyType::Float32) out = static_cast<float>(out);  // the value the type can hold
    return Status::Ok;
  }

  Status skip(PlyType t, std::uint64_t count) {
    for (std::uint64_t i = 0; i < count; ++i) {
      double v = 0;
      const Status s = read(t, v);
      if (s != Status::Ok) return s;
    }
    return Status::Ok;
  }

  std::uint64_t capacity(PlyType) const { return (data_.size() - pos_) / 2 + 1; }

  std::string where() const { return "line " + std::to_string(line_) + ": "; }
  std::string_view last_token() const { return token_; }

 private:
  std::string_view next() {
    while (pos_ < data_.size()) {
      const char c = data_[pos_];
      if (c == '\n') {
        ++line_;
      } else if (!detail::is_blank(c)) {
        break;
      }
      ++pos_;
    }
    const std::size_t start = pos_;
    while (pos_ < data_.size() && data_[pos_] != '\n' && !detail::is_blank(data_[pos_])) ++pos_;
    return data_.substr(start, pos_ - start);
  }

  std::string_view data_;
  std::size_t pos_ = 0;
  std::uint64_t line_;
  std::string_view token_;
};

// ---------------------------------------------------------------------------------------------
// Element readers

struct VertexRoles {
  int x = -1, y = -1, z = -1;
  int nx = -1, ny = -1, nz = -1;
  int r = -1, g = -1, b = -1;
  int u = -1, v = -1;
};

VertexRoles find_vertex_roles(const PlyElement& element, const std::string& name) {
  VertexRoles roles;
  for (int j = 0; j < static_cast<int>(element.properties.size()); ++j) {
    const std::string& p = element.properties[static_cast<std::size_t>(j)].name;
    int* slot = nullptr;
    if (p == "x")
      slot = &roles.x;
    else if (p == "y")
      slot = &roles.y;
    else if (p == "z")
      slot = &roles.z;
    else if (p == "nx")
      slot = &roles.nx;
    else if (p == "ny")
      slot = &roles.ny;
    else if (p == "nz")
      slot = &roles.nz;
    else if (p == "red" || p == "diffuse_red")
      slot = &roles.r;
    else if (p == "green" || p == "diffuse_green")
      slot = &roles.g;
    else if (p == "blue" || p == "diffuse_blue")
      slot = &roles.b;
    else if (p == "u" || p == "s" || p == "texture_u" || p == "texture_s")
      slot = &roles.u;
    else if (p == "v" || p == "t" || p == "texture_v" || p == "texture_t")
      slot = &roles.v;
    if (slot == nullptr || *slot >= 0) continue;  // unknown, or a duplicate alias: ignore
    if (element.properties[static_cast<std::size_t>(j)].is_list) {
      if (slot == &roles.x || slot == &roles.y || slot == &roles.z) {
        throw IoError(name, "vertex property '" + p + "' is a list, expected a scalar");
      }
      continue;
    }
    *slot = j;
  }
  if (roles.x < 0 || roles.y < 0 || roles.z < 0) {
    throw IoError(name, "the 'vertex' element lacks one of the properties x, y, z");
  }
  return roles;
}

std::uint8_t to_color_byte(PlyType t, double v) {
  double scaled = v;
  if (t == PlyType::Float32 || t == PlyType::Float64) {
    scaled = v * 255.0;
  } else if (t == PlyType::UInt16) {
    scaled = v / 257.0;
  }
  if (!(scaled >= 0)) return 0;  // also NaN
  if (scaled >= 255) return 255;
  return static_cast<std::uint8_t>(std::lround(scaled));
}

template <typename Source>
[[noreturn]] void fail_value(const Source& source, Status status, const std::string& name,
                             const PlyElement& element, std::uint64_t i, const PlyProperty& p) {
  if (status == Status::End) {
    throw IoError(name, "truncated data: the file ends inside " + element.name + " " +
                            std::to_string(i) + " (of " + std::to_string(element.count) + ")");
  }
  throw IoError(name, source.where() + "bad value " + quoted(source.last_token()) +
                          " for property '" + p.name + "' of " + element.name + " " +
                          std::to_string(i));
}

/// Reads a list length (any integer type); rejects negative lengths and lengths the remaining
/// data cannot hold.
template <typename Source>
std::uint64_t read_list_count(Source& source, const std::string& name, const PlyElement& element,
                              std::uint64_t i, const PlyProperty& p) {
  double n = 0;
  const Status s = source.read(p.count_type, n);
  if (s != Status::Ok) fail_value(source, s, name, element, i, p);
  if (n < 0) {
    throw IoError(name, source.where() + element.name + " " + std::to_string(i) +
                            " has a negative list length " +
                            std::to_string(static_cast<long long>(n)) + " for property '" + p.name +
                            "'");
  }
  const auto count = static_cast<std::uint64_t>(n);
  if (count > source.capacity(p.type)) {
    throw IoError(name, "truncated data: " + element.name + " " + std::to_string(i) +
                            " announces a list of " + std::to_string(count) + " entries for '" +
                            p.name + "' but the file ends before");
  }
  return count;
}

template <typename Source>
void skip_element(Source& source, const PlyElement& element, const std::string& name) {
  for (std::uint64_t i = 0; i < element.count; ++i) {
    for (const PlyProperty& p : element.properties) {
      std::uint64_t count = 1;
      if (p.is_list) count = read_list_count(source, name, element, i, p);
      const Status s = source.skip(p.type, count);
      if (s != Status::Ok) fail_value(source, s, name, element, i, p);
    }
  }
}

struct VertexData {
  std::vector<double> V, N, UV;
  std::vector<std::uint8_t> C;
  bool normals_ok = false;
  bool uv_ok = false;
};

template <typename Source>
VertexData read_vertices(Source& source, const PlyElement& element, const std::string& name) {
  const VertexRoles roles = find_vertex_roles(element, name);
  VertexData out;
  const bool has_normals = roles.nx >= 0 && roles.ny >= 0 && roles.nz >= 0;
  const bool has_colors = roles.r >= 0 && roles.g >= 0 && roles.b >= 0;
  const bool has_uv = roles.u >= 0 && roles.v >= 0;
  out.normals_ok = has_normals;
  out.uv_ok = has_uv;
  const auto n = static_cast<std::size_t>(element.count);  // bounded by the data size check
  out.V.reserve(3 * n);
  if (has_normals) out.N.reserve(3 * n);
  if (has_colors) out.C.reserve(3 * n);
  if (has_uv) out.UV.reserve(2 * n);
  std::vector<double> values(element.properties.size(), 0.0);
  for (std::uint64_t i = 0; i < element.count; ++i) {
    for (std::size_t j = 0; j < element.properties.size(); ++j) {
      const PlyProperty& p = element.properties[j];
      Status s;
      if (p.is_list) {
        s = source.skip(p.type, read_list_count(source, name, element, i, p));
      } else {
        s = source.read(p.type, values[j]);
      }
      if (s != Status::Ok) fail_value(source, s, name, element, i, p);
    }
    const double xyz[3] = {values[static_cast<std::size_t>(roles.x)],
                           values[static_cast<std::size_t>(roles.y)],
                           values[static_cast<std::size_t>(roles.z)]};
    for (double c : xyz) {
      if (!std::isfinite(c)) {
        throw IoError(name, "vertex " + std::to_string(i) + " has a non-finite coordinate (" +
                                detail::format_double(c) + ")");
      }
      out.V.push_back(c);
    }
    if (has_normals) {
      for (int role : {roles.nx, roles.ny, roles.nz}) {
        const double c = values[static_cast<std::size_t>(role)];
        out.normals_ok = out.normals_ok && std::isfinite(c);
        out.N.push_back(c);
      }
    }
    if (has_colors) {
      for (int role : {roles.r, roles.g, roles.b}) {
        const auto j = static_cast<std::size_t>(role);
        out.C.push_back(to_color_byte(element.properties[j].type, values[j]));
      }
    }
    if (has_uv) {
      for (int role : {roles.u, roles.v}) {
        const double c = values[static_cast<std::size_t>(role)];
        out.uv_ok = out.uv_ok && std::isfinite(c);
        out.UV.push_back(c);
      }
    }
  }
  return out;
}

int find_face_list(const PlyElement& element) {
  for (std::size_t j = 0; j < element.properties.size(); ++j) {
    const PlyProperty& p = element.properties[j];
    if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
      return static_cast<int>(j);
    }
  }
  return -1;
}

/// How an element's index lists make triangles: `face` lists are polygons (at least 3 indices,
/// triangulated by their corner positions); `tristrips` lists are triangle strips separated by
/// the restart index -1.
enum class IndexLists { Polygons, Strips };

/// One element's index lists as read, triangulated once the vertices are known (a face element
/// may come before the vertex element): polygons stored as `count, c0, c1, ...`, strips as they
/// are in the file (separated by -1).
struct IndexListData {
  IndexLists kind = IndexLists::Polygons;
  std::vector<Index> indices;
};

/// Appends the triangles of `lists` to `tris`; `V` holds the vertices (3 doubles each).
void append_triangles(const IndexListData& lists, const std::vector<double>& V,
                      std::vector<Index>& tris) {
  const std::vector<Index>& in = lists.indices;
  if (lists.kind == IndexLists::Polygons) {
    detail::PolygonTriangulator triangulator;
    for (std::size_t k = 0; k < in.size(); k += 1 + static_cast<std::size_t>(in[k])) {
      triangulator.append(V, in.data() + k + 1, static_cast<std::size_t>(in[k]), tris);
    }
    return;
  }
  std::size_t start = 0;
  for (std::size_t k = 0; k <= in.size(); ++k) {
    if (k < in.size() && in[k] >= 0) continue;
    mesh::append_strip_triangles(in.data() + start, k - start, tris);
    start = k + 1;
  }
}

template <typename Source>
IndexListData read_index_lists(Source& source, const PlyElement& element,
                               std::uint64_t num_vertices, IndexLists kind,
                               const std::string& name) {
  const int list = find_face_list(element);
  if (list < 0 && element.count > 0) {
    throw IoError(name, "the '" + element.name +
                            "' element has no 'vertex_indices' (or 'vertex_index') list property");
  }
  IndexListData out;
  out.kind = kind;
  if (list >= 0 && kind == IndexLists::Polygons) {
    // A face holds at least 3 indices, so the remaining data bounds what to reserve (the
    // header's count alone could be a lie far beyond the file size).
    const PlyType index_type = element.properties[static_cast<std::size_t>(list)].type;
    out.indices.reserve(
        4 * static_cast<std::size_t>(std::min(element.count, source.capacity(index_type) / 3)));
  }
  const double lowest = kind == IndexLists::Strips ? -1.0 : 0.0;  // -1 restarts a strip
  for (std::uint64_t i = 0; i < element.count; ++i) {
    for (std::size_t j = 0; j < element.properties.size(); ++j) {
      const PlyProperty& p = element.properties[j];
      if (static_cast<int>(j) != list) {
        std::uint64_t count = 1;
        if (p.is_list) count = read_list_count(source, name, element, i, p);
        const Status s = source.skip(p.type, count);
        if (s != Status::Ok) fail_value(source, s, name, element, i, p);
        continue;
      }
      const std::uint64_t count = read_list_count(source, name, element, i, p);
      if (kind == IndexLists::Polygons && count < 3) {
        throw IoError(name, source.where() + "face " + std::to_string(i) + " has " +
                                plural(count, "vertex index", "vertex indices") +
                                " (a face needs at least 3)");
      }
      if (kind == IndexLists::Polygons) out.indices.push_back(static_cast<Index>(count));
      for (std::uint64_t k = 0; k < count; ++k) {
        double v = 0;
        const Status s = source.read(p.type, v);
        if (s != Status::Ok) fail_value(source, s, name, element, i, p);
        if (!(v >= lowest && v < static_cast<double>(num_vertices) && v == std::floor(v))) {
          throw IoError(name, source.where() + element.name + " " + std::to_string(i) +
                                  " references vertex " + detail::format_double(v) +
                                  " but the file has " +
                                  plural(num_vertices, "vertex", "vertices"));
        }
        out.indices.push_back(static_cast<Index>(v));
      }
      if (kind == IndexLists::Strips) out.indices.push_back(-1);
    }
  }
  return out;
}

template <typename Source>
TriangleMesh read_body(Source& source, const PlyHeader& header, const std::string& name) {
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  const PlyElement* strips = nullptr;
  for (const PlyElement& e : header.elements) {
    const PlyElement** slot = e.name == "vertex"      ? &vertex
                              : e.name == "face"      ? &face
                              : e.name == "tristrips" ? &strips
                                                      : nullptr;
    if (slot == nullptr) continue;
    if (*slot != nullptr) throw IoError(name, "the header has two '" + e.name + "' elements");
    *slot = &e;
  }
  if (vertex == nullptr) throw IoError(name, "the header has no 'vertex' element");
  if (vertex->count == 0) throw IoError(name, "the file has no vertices");
  if (vertex->count > static_cast<std::uint64_t>(std::numeric_limits<Index>::max())) {
    throw IoError(name, "too many vertices (" + std::to_string(vertex->count) + ")");
  }
  find_vertex_roles(*vertex, name);  // fail on missing x,y,z before reading anything

  VertexData vertices;
  std::vector<IndexListData> lists;
  for (const PlyElement& e : header.elements) {
    if (e.properties.empty()) continue;  // nothing stored, whatever the count
    if (&e == vertex) {
      vertices = read_vertices(source, e, name);
    } else if (&e == face || &e == strips) {
      lists.push_back(read_index_lists(
          source, e, vertex->count, &e == face ? IndexLists::Polygons : IndexLists::Strips, name));
    } else {
      skip_element(source, e, name);
    }
  }

  std::vector<Index> tris;
  for (const IndexListData& l : lists) append_triangles(l, vertices.V, tris);
  TriangleMesh mesh;
  mesh.V = detail::to_points(vertices.V);
  mesh.F = detail::to_triangles(tris);
  if (vertices.normals_ok) mesh.N = detail::to_points(vertices.N);
  if (!vertices.C.empty()) mesh.C = detail::to_colors(vertices.C);
  if (vertices.uv_ok) {
    mesh.UV = detail::to_texcoords(vertices.UV);
    mesh.FUV = mesh.F;
  }
  return mesh;
}


/// The layout of most scanners' binary PLYs, read straight into the mesh (no per-value
/// dispatch through a data source, no intermediate arrays): native byte order, a 'vertex'
/// element of scalar properties followed by a 'face' element whose only property is a
/// 'vertex_indices' list with a uchar count and int/uint indices. Returns nullopt when the file
/// has another layout or anything unusual (a face that is not a triangle, an index out of range,
/// a non-finite coordinate, truncated data): the general reader then reads it and reports any
/// problem. When it returns a mesh, the mesh equals what the general reader gives.
std::optional<TriangleMesh> read_simple_binary(const PlyHeader& header, std::string_view data) {
  const PlyFormat native = std::endian::native == std::endian::little ? PlyFormat::BinaryLittle
                                                                      : PlyFormat::BinaryBig;
  if (header.format != native || header.elements.size() != 2) return std::nullopt;
  const PlyElement& vertex = header.elements[0];
  const PlyElement& face = header.elements[1];
  if (vertex.name != "vertex" || face.name != "face" || vertex.count == 0 ||
      vertex.count > static_cast<std::uint64_t>(std::numeric_limits<Index>::max()) ||
      face.properties.size() != 1) {
    return std::nullopt;
  }
  const PlyProperty& list = face.properties[0];
  if (!list.is_list || list.count_type != PlyType::UInt8 ||
      (list.type != PlyType::Int32 && list.type != PlyType::UInt32) ||
      (list.name != "vertex_indices" && list.name != "vertex_index")) {
    return std::nullopt;
  }
  std::vector<std::size_t> offset(vertex.properties.size());
  std::size_t stride = 0;
  for (std::size_t j = 0; j < vertex.properties.size(); ++j) {
    if (vertex.properties[j].is_list) return std::nullopt;
    offset[j] = stride;
    stride += type_size(vertex.properties[j].type);
  }
  VertexRoles roles;
  try {
    roles = find_vertex_roles(vertex, "");
  } catch (const IoError&) {
    return std::nullopt;
  }
  const auto nv = static_cast<std::size_t>(vertex.count);
  const auto nf = static_cast<std::size_t>(face.count);
  constexpr std::size_t kFaceBytes = 1 + 3 * 4;
  if (nv > data.size() / stride || nf > (data.size() - nv * stride) / kFaceBytes) {
    return std::nullopt;
  }
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  const bool has_normals = roles.nx >= 0 && roles.ny >= 0 && roles.nz >= 0;
  const bool has_colors = roles.r >= 0 && roles.g >= 0 && roles.b >= 0;
  const bool has_uv = roles.u >= 0 && roles.v >= 0;
  auto role = [&](int j) {
    const auto k = static_cast<std::size_t>(j);
    return std::pair<std::size_t, PlyType>(offset[k], vertex.properties[k].type);
  };
  // out (nv rows) = convert(type, value) of the vertex properties `cols` (offset, type), row by row.
  auto gather = [&](auto& out, std::initializer_list<int> cols, auto convert) {
    std::pair<std::size_t, PlyType> c[3];
    int n = 0;
    for (int j : cols) c[n++] = role(j);
    out.resize(static_cast<Eigen::Index>(nv), n);
    auto* dst = out.data();
    for (std::size_t i = 0; i < nv; ++i) {
      for (int k = 0; k < n; ++k) {
        dst[static_cast<std::size_t>(n) * i + static_cast<std::size_t>(k)] =
            convert(c[k].second, load_scalar(bytes + i * stride + c[k].first, c[k].second));
      }
    }
  };
  const auto as_is = [](PlyType, double v) { return v; };
  TriangleMesh mesh;
  const auto rows = static_cast<Eigen::Index>(nv);
  {
    const std::pair<std::size_t, PlyType> xyz[3] = {role(roles.x), role(roles.y), role(roles.z)};
    mesh.V.resize(rows, 3);
    double* V = mesh.V.data();
    if (xyz[0].second == PlyType::Float32 && xyz[1].second == PlyType::Float32 &&
        xyz[2].second == PlyType::Float32) {  // the usual case, without a switch per value
      for (std::size_t i = 0; i < nv; ++i) {
        const unsigned char* rec = bytes + i * stride;
        for (int k = 0; k < 3; ++k) {
          float c;
          std::memcpy(&c, rec + xyz[k].first, 4);
          V[3 * i + static_cast<std::size_t>(k)] = c;
        }
      }
    } else {
      gather(mesh.V, {roles.x, roles.y, roles.z}, as_is);
    }
    if (!mesh.V.allFinite()) return std::nullopt;
  }
  if (has_normals) {
    gather(mesh.N, {roles.nx, roles.ny, roles.nz}, as_is);
    if (!mesh.N.allFinite()) mesh.N.resize(0, 3);
  }
  if (has_colors) gather(mesh.C, {roles.r, roles.g, roles.b}, to_color_byte);
  if (has_uv) {
    gather(mesh.UV, {roles.u, roles.v}, as_is);
    if (!mesh.UV.allFinite()) mesh.UV.resize(0, 2);
  }
  // Faces: triangles only; one with a repeated corner is dropped (as the triangulator does).
  mesh.F.resize(static_cast<Eigen::Index>(nf), 3);
  Index* F = mesh.F.data();
  std::size_t kept = 0;
  const unsigned char* rec = bytes + nv * stride;
  for (std::size_t i = 0; i < nf; ++i, rec += kFaceBytes) {
    if (rec[0] != 3) return std::nullopt;
    std::uint32_t c[3];
    std::memcpy(c, rec + 1, 12);
    // A negative int32 index reads as a uint32 >= 2^31 > nv: out of range as well.
    if (c[0] >= nv || c[1] >= nv || c[2] >= nv) return std::nullopt;
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
    for (int k = 0; k < 3; ++k) F[3 * kept + static_cast<std::size_t>(k)] = static_cast<Index>(c[k]);
    ++kept;
  }
  if (kept != nf) mesh.F.conservativeResize(static_cast<Eigen::Index>(kept), 3);
  if (mesh.UV.rows() != 0) mesh.FUV = mesh.F;
  return mesh;
}

}  // namespace

TriangleMesh read_ply_from_memory(std::string_view bytes, const std::string& name) {
  const PlyHeader header = parse_header(bytes, name);
  const std::string_view data = bytes.substr(header.data_offset);
  check_counts_against_size(header, data.size(), name);
  if (header.format == PlyFormat::Ascii) {
    AsciiSource source(data, header.lines + 1);
    return read_body(source, header, name);
  }
  if (std::optional<TriangleMesh> mesh = read_simple_binary(header, data)) return std::move(*mesh);
  BinarySource source(data, header.format == PlyFormat::BinaryBig);
  return read_body(source, header, name);
}

TriangleMesh read_ply(const std::filesystem::path& path) {
  const detail::MappedFile file(path);
  return read_ply_from_memory(file.bytes(), path.string());
}

}  // namespace breastfit::io
