#include "breastfit/io/read_obj.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/io/detail/file_bytes.h"
#include "breastfit/io/detail/mesh_arrays.h"
#include "breastfit/io/detail/polygon_triangulation.h"
#include "breastfit/io/detail/text.h"

namespace breastfit::io {
namespace {

using detail::quoted;

constexpr Index kNone = -1;
constexpr std::size_t kMaxIndex = static_cast<std::size_t>(std::numeric_limits<Index>::max());

struct ObjData {
  std::vector<double> V;      // 3 per vertex
  std::vector<double> C;      // 3 per vertex (raw values) when every vertex has colours
  std::vector<double> UV;     // 2 per vt
  std::vector<double> VN;     // 3 per vn
  std::vector<Index> tris;    // 3 per triangle
  std::vector<Index> tri_uv;  // 3 per triangle (kNone when the face had no vt)
  std::vector<Index> tri_vn;  // 3 per triangle (kNone when the corner had no vn)
  bool all_vertices_colored = true;
  bool all_faces_have_uv = true;
  bool any_corner_has_vn = false;
  bool normals_finite = true;
};

class ObjParser {
 public:
  ObjParser(const std::string& name) : name_(name) {}

  void statement(std::string_view line, std::uint64_t line_no) {
    line_no_ = line_no;
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    const std::string_view keyword = detail::next_token(line);
    if (keyword == "v") {
      vertex(line);
    } else if (keyword == "vt") {
      texcoord(line);
    } else if (keyword == "vn") {
      normal(line);
    } else if (keyword == "f" || keyword == "fo") {
      face(line);
    }
    // Everything else (g, o, s, usemtl, mtllib, l, p, vp, curves, unknown) is ignored.
  }

  ObjData& data() { return data_; }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw IoError(name_, "line " + std::to_string(line_no_) + ": " + problem);
  }

  /// Parses up to `max` numbers; returns how many were read.
  int numbers(std::string_view line, double* out, int max, const char* what) const {
    int n = 0;
    while (true) {
      const std::string_view token = detail::next_token(line);
      if (token.empty()) break;
      double v = 0;
      if (!detail::parse_double(token, v)) {
        fail("bad number " + quoted(token) + " in a '" + what + "' statement");
      }
      if (n < max) out[n] = v;
      ++n;
    }
    return std::min(n, max);
  }

  void vertex(std::string_view line) {
    double v[7] = {0, 0, 0, 0, 0, 0, 0};
    const int n = numbers(line, v, 7, "v");
    if (n < 3) fail("a vertex needs 3 coordinates, found " + std::to_string(n));
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(v[k])) {
        fail("vertex " + std::to_string(data_.V.size() / 3 + 1) + " has a non-finite coordinate (" +
             detail::format_double(v[k]) + ")");
      }
    }
    if (data_.V.size() / 3 >= kMaxIndex) fail("too many vertices");
    data_.V.insert(data_.V.end(), v, v + 3);
    if (n >= 6 && data_.all_vertices_colored) {
      data_.C.insert(data_.C.end(), v + 3, v + 6);
    } else {
      data_.all_vertices_colored = false;
      data_.C.clear();
    }
  }

  void texcoord(std::string_view line) {
    double t[3] = {0, 0, 0};
    const int n = numbers(line, t, 3, "vt");
    if (n < 1) fail("a texture coordinate needs at least 1 value");
    if (!std::isfinite(t[0]) || !std::isfinite(t[1])) fail("non-finite texture coordinate");
    if (data_.UV.size() / 2 >= kMaxIndex) fail("too many texture coordinates");
    data_.UV.insert(data_.UV.end(), t, t + 2);
  }

  void normal(std::string_view line) {
    double nrm[3] = {0, 0, 0};
    const int n = numbers(line, nrm, 3, "vn");
    if (n < 3) fail("a normal needs 3 components, found " + std::to_string(n));
    for (double c : nrm) data_.normals_finite = data_.normals_finite && std::isfinite(c);
    if (data_.VN.size() / 3 >= kMaxIndex) fail("too many normals");
    data_.VN.insert(data_.VN.end(), nrm, nrm + 3);
  }

  /// Resolves a 1-based or negative (relative) OBJ index against `count` defined so far.
  Index resolve(std::string_view token, std::size_t count, const char* what) const {
    std::int64_t i = 0;
    if (!detail::parse_int64(token, i))
      fail("bad " + std::string(what) + " index " + quoted(token));
    if (i == 0) fail(std::string(what) + " index 0 is invalid (OBJ indices start at 1)");
    const auto n = static_cast<std::int64_t>(count);
    const std::int64_t resolved = i > 0 ? i - 1 : n + i;
    if (resolved < 0 || resolved >= n) {
      const std::string noun = std::string(what) == "vertex"
                                   ? (count == 1 ? "vertex is" : "vertices are")
                                   : std::string(what) + (count == 1 ? " is" : "s are");
      fail("face references " + std::string(what) + " " + std::to_string(i) + " but " +
           std::to_string(count) + " " + noun + " defined so far");
    }
    return static_cast<Index>(resolved);
  }

  void face(std::string_view line) {
    v_.clear();
    vt_.clear();
    vn_.clear();
    bool face_has_uv = true;
    while (true) {
      const std::string_view token = detail::next_token(line);
      if (token.empty()) break;
      const std::size_t s1 = token.find('/');
      const std::string_view vpart = token.substr(0, s1);
      std::string_view tpart;
      std::string_view npart;
      if (s1 != std::string_view::npos) {
        const std::string_view rest = token.substr(s1 + 1);
        const std::size_t s2 = rest.find('/');
        tpart = rest.substr(0, s2);
        if (s2 != std::string_view::npos) {
          npart = rest.substr(s2 + 1);
          if (npart.find('/') != std::string_view::npos) fail("bad face corner " + quoted(token));
        }
      }
      v_.push_back(resolve(vpart, data_.V.size() / 3, "vertex"));
      if (tpart.empty()) {
        face_has_uv = false;
        vt_.push_back(kNone);
      } else {
        vt_.push_back(resolve(tpart, data_.UV.size() / 2, "texture coordinate"));
      }
      if (npart.empty()) {
        vn_.push_back(kNone);
      } else {
        vn_.push_back(resolve(npart, data_.VN.size() / 3, "normal"));
        data_.any_corner_has_vn = true;
      }
    }
    if (v_.size() < 3) {
      fail("face has " + std::to_string(v_.size()) + " vert" + (v_.size() == 1 ? "ex" : "ices") +
           " (a face needs at least 3)");
    }
    positions_.clear();
    for (Index v : v_) {
      const auto at = 3 * static_cast<std::size_t>(v);
      positions_.emplace_back(data_.V[at], data_.V[at + 1], data_.V[at + 2]);
    }
    detail::triangulate_polygon(positions_, triangles_);
    for (const auto& c : triangles_) {
      if (v_[c[0]] == v_[c[1]] || v_[c[1]] == v_[c[2]] || v_[c[0]] == v_[c[2]]) continue;
      for (std::size_t k : c) {
        data_.tris.push_back(v_[k]);
        data_.tri_uv.push_back(face_has_uv ? vt_[k] : kNone);
        data_.tri_vn.push_back(vn_[k]);
      }
      if (!face_has_uv) data_.all_faces_have_uv = false;
    }
  }

  const std::string& name_;
  std::uint64_t line_no_ = 0;
  ObjData data_;
  std::vector<Index> v_, vt_, vn_;
  std::vector<Vec3> positions_;                        // of the face's corners
  std::vector<std::array<std::size_t, 3>> triangles_;  // of the face, as corner triples
};

/// Per-vertex normals from the corners' vn indices: a vertex whose corners all use one vn gets
/// it exactly; conflicting ones get the normalised average. Empty when some vertex has none.
Points vertex_normals(const ObjData& d, Eigen::Index num_vertices) {
  const Eigen::Index num_vn = static_cast<Eigen::Index>(d.VN.size() / 3);
  Points VN(num_vn, 3);
  for (Eigen::Index i = 0; i < VN.size(); ++i) VN.data()[i] = d.VN[static_cast<std::size_t>(i)];
  if (!d.normals_finite || num_vn == 0) return {};
  if (!d.any_corner_has_vn) {
    if (num_vn == num_vertices) return VN;  // point cloud / unreferenced: one vn per v
    return {};
  }
  std::vector<Index> first(static_cast<std::size_t>(num_vertices), kNone);
  std::vector<char> conflict(static_cast<std::size_t>(num_vertices), 0);
  for (std::size_t k = 0; k < d.tris.size(); ++k) {
    const Index n = d.tri_vn[k];
    if (n == kNone) continue;
    const auto v = static_cast<std::size_t>(d.tris[k]);
    if (first[v] == kNone) {
      first[v] = n;
    } else if (first[v] != n) {
      conflict[v] = 1;
    }
  }
  Points N = Points::Zero(num_vertices, 3);
  for (std::size_t k = 0; k < d.tris.size(); ++k) {
    const Index n = d.tri_vn[k];
    const auto v = static_cast<std::size_t>(d.tris[k]);
    if (n != kNone && conflict[v]) N.row(static_cast<Eigen::Index>(v)) += VN.row(n);
  }
  for (Eigen::Index v = 0; v < num_vertices; ++v) {
    const auto s = static_cast<std::size_t>(v);
    if (first[s] == kNone) {
      if (num_vn == num_vertices) {
        N.row(v) = VN.row(v);
        continue;
      }
      return {};
    }
    if (conflict[s]) {
      const double len = N.row(v).norm();
      if (len > 0) N.row(v) /= len;
    } else {
      N.row(v) = VN.row(first[s]);
    }
  }
  return N;
}

}  // namespace

TriangleMesh read_obj_from_memory(std::string_view bytes, const std::string& name) {
  if (bytes.empty()) throw IoError(name, "empty file");
  if (std::memchr(bytes.data(), '\0', bytes.size()) != nullptr) {
    throw IoError(name, "contains NUL bytes: binary data, not a text OBJ file");
  }
  ObjParser parser(name);
  std::string joined;
  std::size_t pos = 0;
  std::uint64_t line_no = 0;
  while (pos < bytes.size()) {
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string_view::npos) end = bytes.size();
    std::string_view line = bytes.substr(pos, end - pos);
    pos = end + 1;
    const std::uint64_t first_line = ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (!line.empty() && line.back() == '\\') {
      joined.assign(line.substr(0, line.size() - 1));
      while (pos < bytes.size()) {
        std::size_t e = bytes.find('\n', pos);
        if (e == std::string_view::npos) e = bytes.size();
        std::string_view next = bytes.substr(pos, e - pos);
        pos = e + 1;
        ++line_no;
        if (!next.empty() && next.back() == '\r') next.remove_suffix(1);
        joined += ' ';
        if (!next.empty() && next.back() == '\\') {
          joined.append(next.substr(0, next.size() - 1));
        } else {
          joined.append(next);
          break;
        }
      }
      line = joined;
    }
    parser.statement(line, first_line);
  }

  ObjData& d = parser.data();
  if (d.V.empty()) throw IoError(name, "no vertices ('v' statements) found: not an OBJ file?");
  TriangleMesh mesh;
  mesh.V = detail::to_points(d.V);
  mesh.F = detail::to_triangles(d.tris);
  if (d.all_vertices_colored && d.C.size() == d.V.size()) {
    double max_value = 0;
    for (double c : d.C) max_value = std::max(max_value, std::isfinite(c) ? c : 0.0);
    const double scale = max_value <= 1.0 ? 255.0 : 1.0;
    mesh.C.resize(mesh.V.rows(), 3);
    for (std::size_t i = 0; i < d.C.size(); ++i) {
      const double c = d.C[i] * scale;
      mesh.C.data()[i] = !(c > 0) ? 0 : c >= 255 ? 255 : static_cast<std::uint8_t>(std::lround(c));
    }
  }
  if (!d.tris.empty() && d.all_faces_have_uv && !d.UV.empty()) {
    mesh.UV = detail::to_texcoords(d.UV);
    mesh.FUV = detail::to_triangles(d.tri_uv);
  }
  mesh.N = vertex_normals(d, mesh.V.rows());
  return mesh;
}

TriangleMesh read_obj(const std::filesystem::path& path) {
  return read_obj_from_memory(detail::read_file_bytes(path), path.string());
}

}  // namespace breastfit::io
