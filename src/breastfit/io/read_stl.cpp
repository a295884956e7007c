#include "breastfit/io/read_stl.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/io/detail/mapped_file.h"
#include "breastfit/io/detail/mesh_arrays.h"
#include "breastfit/io/detail/text.h"
#include "breastfit/mesh/index_triangulation.h"

namespace breastfit::io {
namespace {

using detail::quoted;

constexpr std::size_t kHeaderBytes = 84;
constexpr std::size_t kTriangleBytes = 50;

/// Merges exactly identical vertices (-0 and +0 count as equal) into an indexed mesh, numbering
/// them in order of first appearance. Open addressing with linear probing over the vertex array.
class VertexMerger {
 public:
  explicit VertexMerger(std::size_t expected) {
    std::size_t size = 64;
    while (size < 2 * expected) size *= 2;
    table_.assign(size, kEmpty);
    V_.reserve(3 * expected);
  }

  Index add(double x, double y, double z) {
    if (x == 0) x = 0;  // -0 == +0
    if (y == 0) y = 0;
    if (z == 0) z = 0;
    const std::size_t mask = table_.size() - 1;
    for (std::size_t h = hash(x, y, z) & mask;; h = (h + 1) & mask) {
      const Index v = table_[h];
      if (v == kEmpty) break;
      const double* p = &V_[3 * static_cast<std::size_t>(v)];
      if (p[0] == x && p[1] == y && p[2] == z) return v;
    }
    const auto index = static_cast<Index>(V_.size() / 3);
    V_.push_back(x);
    V_.push_back(y);
    V_.push_back(z);
    if (2 * (V_.size() / 3) > table_.size()) {
      grow();  // re-inserts every vertex, this one included
    } else {
      insert(index, mask);
    }
    return index;
  }

  const std::vector<double>& vertices() const { return V_; }

 private:
  static constexpr Index kEmpty = -1;

  static std::uint64_t mix(std::uint64_t x) {  // splitmix64 finaliser
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
  }
  static std::size_t hash(double x, double y, double z) {
    return static_cast<std::size_t>(
        mix(std::bit_cast<std::uint64_t>(x) ^
            mix(std::bit_cast<std::uint64_t>(y) ^ mix(std::bit_cast<std::uint64_t>(z)))));
  }
  void insert(Index v, std::size_t mask) {
    const double* p = &V_[3 * static_cast<std::size_t>(v)];
    std::size_t h = hash(p[0], p[1], p[2]) & mask;
    while (table_[h] != kEmpty) h = (h + 1) & mask;
    table_[h] = v;
  }
  void grow() {
    table_.assign(table_.size() * 2, kEmpty);
    const std::size_t mask = table_.size() - 1;
    for (std::size_t v = 0; v < V_.size() / 3; ++v) insert(static_cast<Index>(v), mask);
  }

  std::vector<Index> table_;
  std::vector<double> V_;
};

TriangleMesh finish(const VertexMerger& merger, const std::vector<Index>& tris,
                    const std::string& name) {
  if (merger.vertices().empty()) throw IoError(name, "the file has no triangles");
  TriangleMesh mesh;
  mesh.V = detail::to_points(merger.vertices());
  mesh.F = detail::to_triangles(tris);
  return mesh;
}

TriangleMesh read_binary(std::string_view bytes, std::uint32_t count, const std::string& name) {
  VertexMerger merger(std::min<std::size_t>(count, 1u << 20));
  std::vector<Index> tris;
  tris.reserve(3 * static_cast<std::size_t>(count));  // count matches the file size
  const char* p = bytes.data() + kHeaderBytes;
  for (std::uint32_t t = 0; t < count; ++t, p += kTriangleBytes) {
    Index corners[3];
    for (int k = 0; k < 3; ++k) {
      float xyz[3];
      std::memcpy(xyz, p + 12 + 12 * k, 12);
      if constexpr (std::endian::native == std::endian::big) {
        for (float& f : xyz)
          f = std::bit_cast<float>(__builtin_bswap32(std::bit_cast<std::uint32_t>(f)));
      }
      for (float f : xyz) {
        if (!std::isfinite(f)) {
          throw IoError(name, "triangle " + std::to_string(t) + " has a non-finite coordinate (" +
                                  detail::format_float(f) + ")");
        }
      }
      corners[k] = merger.add(xyz[0], xyz[1], xyz[2]);
    }
    mesh::append_fan_triangles(corners, 3, tris);
  }
  return finish(merger, tris, name);
}

TriangleMesh read_ascii(std::string_view bytes, const std::string& name) {
  VertexMerger merger(1024);
  std::vector<Index> tris;
  std::vector<Index> loop;
  bool in_loop = false;
  std::uint64_t facets = 0;
  std::size_t pos = 0;
  std::uint64_t line_no = 0;
  while (pos < bytes.size()) {
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string_view::npos) end = bytes.size();
    std::string_view line = bytes.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    const std::string at = "line " + std::to_string(line_no) + ": ";
    const std::string_view keyword = detail::next_token(line);
    if (keyword.empty() || keyword == "solid" || keyword == "endsolid" || keyword == "facet" ||
        keyword == "endfacet") {
      continue;  // facet normals are ignored; solid names are free text
    }
    if (keyword == "outer") {
      if (in_loop) throw IoError(name, at + "'outer loop' inside an open loop");
      in_loop = true;
      loop.clear();
    } else if (keyword == "vertex") {
      if (!in_loop) throw IoError(name, at + "'vertex' outside an 'outer loop'");
      double xyz[3];
      for (double& c : xyz) {
        const std::string_view token = detail::next_token(line);
        if (!detail::parse_double(token, c)) {
          throw IoError(name, at + "bad vertex coordinate " + quoted(token));
        }
        if (!std::isfinite(c)) {
          throw IoError(name, at + "non-finite vertex coordinate " + quoted(token));
        }
      }
      loop.push_back(merger.add(xyz[0], xyz[1], xyz[2]));
    } else if (keyword == "endloop") {
      if (!in_loop) throw IoError(name, at + "'endloop' without 'outer loop'");
      if (loop.size() < 3) {
        throw IoError(name, at + "facet " + std::to_string(facets) + " has " +
                                std::to_string(loop.size()) + " vertices (a facet needs 3)");
      }
      mesh::append_fan_triangles(loop.data(), loop.size(), tris);
      in_loop = false;
      ++facets;
    } else {
      throw IoError(name, at + "unexpected " + quoted(keyword) + " in an ASCII STL file");
    }
  }
  if (in_loop) throw IoError(name, "truncated: the file ends inside a facet");
  return finish(merger, tris, name);
}

}  // namespace

TriangleMesh read_stl_from_memory(std::string_view bytes, const std::string& name) {
  if (bytes.empty()) throw IoError(name, "empty file");
  std::uint32_t count = 0;
  if (bytes.size() >= kHeaderBytes) {
    std::memcpy(&count, bytes.data() + 80, 4);
    if constexpr (std::endian::native == std::endian::big) count = __builtin_bswap32(count);
    if (kHeaderBytes + kTriangleBytes * static_cast<std::uint64_t>(count) == bytes.size()) {
      return read_binary(bytes, count, name);
    }
  }
  std::string_view start = bytes;
  while (!start.empty() && (detail::is_blank(start.front()) || start.front() == '\n')) {
    start.remove_prefix(1);
  }
  if (start.substr(0, 5) == "solid") {
    if (std::memchr(bytes.data(), '\0', bytes.size()) != nullptr) {
      throw IoError(name,
                    "starts with 'solid' but contains NUL bytes, and its size does not "
                    "match a binary STL triangle count");
    }
    return read_ascii(bytes, name);
  }
  if (bytes.size() < kHeaderBytes) {
    throw IoError(name, "too short for a binary STL (" + std::to_string(bytes.size()) +
                            " bytes, need at least 84) and not an ASCII STL (no 'solid')");
  }
  throw IoError(name, "binary STL header announces " + std::to_string(count) +
                          " triangles (84 + 50*" + std::to_string(count) +
                          " bytes) but the file has " + std::to_string(bytes.size()) + " bytes");
}

TriangleMesh read_stl(const std::filesystem::path& path) {
  const detail::MappedFile file(path);
  return read_stl_from_memory(file.bytes(), path.string());
}

}  // namespace breastfit::io
