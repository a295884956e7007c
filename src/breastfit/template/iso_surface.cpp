#include "breastfit/template/iso_surface.h"

#include <array>
#include <cmath>
#include <vector>

#include "breastfit/core/errors.h"

namespace breastfit::templ {

TriangleMesh marching_tetrahedra(const std::function<double(const Vec3&)>& field, const Vec3& lo,
                                 const Vec3& hi, double step) {
  if (!(step > 0)) throw InvalidInput("marching_tetrahedra: step must be > 0");
  const Vec3 ext = hi - lo;
  if (!(ext.minCoeff() > step)) throw InvalidInput("marching_tetrahedra: empty box");
  const int nx = static_cast<int>(std::ceil(ext.x() / step)) + 1;
  const int ny = static_cast<int>(std::ceil(ext.y() / step)) + 1;
  const int nz = static_cast<int>(std::ceil(ext.z() / step)) + 1;
  auto node = [&](int i, int j, int k) { return (static_cast<std::int64_t>(k) * ny + j) * nx + i; };
  auto node_pos = [&](std::int64_t id) {
    const int i = static_cast<int>(id % nx);
    const int j = static_cast<int>((id / nx) % ny);
    const int k = static_cast<int>(id / (static_cast<std::int64_t>(nx) * ny));
    return Vec3(lo.x() + i * step, lo.y() + j * step, lo.z() + k * step);
  };
  const std::int64_t nn = static_cast<std::int64_t>(nx) * ny * nz;
  std::vector<double> val(nn);
  for (std::int64_t id = 0; id < nn; ++id) {
    double v = field(node_pos(id));
    if (v == 0.0) v = 1e-9;
    val[id] = v;
  }
  // Edge vertices: edges of Kuhn tetrahedra join componentwise-ordered corners; the offset
  // (dx, dy, dz) in {0,1}^3 \ {0} gives 7 edge codes per lower node.
  std::vector<Index> edge_vertex(static_cast<size_t>(nn) * 7, -1);
  std::vector<Vec3> verts;
  std::vector<std::array<Index, 3>> tris;
  auto edge_point = [&](std::int64_t a, std::int64_t b, int code) -> Index {
    // a is the lower corner, code = dx + 2 dy + 4 dz - 1.
    Index& slot = edge_vertex[static_cast<size_t>(a) * 7 + code];
    if (slot >= 0) return slot;
    const double fa = val[a], fb = val[b];
    const double t = fa / (fa - fb);
    verts.push_back(node_pos(a) + t * (node_pos(b) - node_pos(a)));
    slot = static_cast<Index>(verts.size() - 1);
    return slot;
  };
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k + 1 < nz; ++k) {
    for (int j = 0; j + 1 < ny; ++j) {
      for (int i = 0; i + 1 < nx; ++i) {
        // Quick reject: all 8 corners the same sign.
        int npos = 0;
        for (int c = 0; c < 8; ++c) npos += val[node(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))] > 0;
        if (npos == 0 || npos == 8) continue;
        for (const auto& pm : perms) {
          std::array<int, 4> bits{};  // corner offsets as bit masks
          bits[0] = 0;
          bits[1] = 1 << pm[0];
          bits[2] = bits[1] | (1 << pm[1]);
          bits[3] = 7;
          std::array<std::int64_t, 4> ids;
          for (int c = 0; c < 4; ++c)
            ids[c] = node(i + (bits[c] & 1), j + ((bits[c] >> 1) & 1), k + ((bits[c] >> 2) & 1));
          std::array<int, 4> in{}, out{};
          int ni = 0, no = 0;
          for (int c = 0; c < 4; ++c) {
            if (val[ids[c]] < 0) in[ni++] = c; else out[no++] = c;
          }
          if (ni == 0 || ni == 4) continue;
          auto ep = [&](int c0, int c1) {
            int lo_c = c0, hi_c = c1;
            if (bits[lo_c] > bits[hi_c]) std::swap(lo_c, hi_c);  // chain order: subset => smaller
            const int code = (bits[hi_c] ^ bits[lo_c]) - 1;
            return edge_point(ids[lo_c], ids[hi_c], code);
          };
          Vec3 cin = Vec3::Zero(), cout = Vec3::Zero();
          for (int a = 0; a < ni; ++a) cin += node_pos(ids[in[a]]);
          for (int a = 0; a < no; ++a) cout += node_pos(ids[out[a]]);
          const Vec3 dir = cout / no - cin / ni;
          auto emit = [&](Index a, Index b, Index c) {
            if (a == b || b == c || a == c) return;
            const Vec3 n = (verts[b] - verts[a]).cross(verts[c] - verts[a]);
            if (n.dot(dir) < 0) std::swap(b, c);
            tris.push_back({a, b, c});
          };
          if (ni == 1 || ni == 3) {
            const int s = ni == 1 ? in[0] : out[0];
            std::array<int, 3> o{};
            int m = 0;
            for (int c = 0; c < 4; ++c)
              if (c != s) o[m++] = c;
            emit(ep(s, o[0]), ep(s, o[1]), ep(s, o[2]));
          } else {
            const Index p00 = ep(in[0], out[0]), p01 = ep(in[0], out[1]);
            const Index p11 = ep(in[1], out[1]), p10 = ep(in[1], out[0]);
            // Quad p00 - p01 - p11 - p10.
            emit(p00, p01, p11);
            emit(p00, p11, p10);
          }
        }
      }
    }
  }
  TriangleMesh m;
  m.V.resize(static_cast<Index>(verts.size()), 3);
  for (size_t v = 0; v < verts.size(); ++v) m.V.row(static_cast<Index>(v)) = verts[v].transpose();
  m.F.resize(static_cast<Index>(tris.size()), 3);
  for (size_t f = 0; f < tris.size(); ++f)
    for (int c = 0; c < 3; ++c) m.F(static_cast<Index>(f), c) = tris[f][c];
  return m;
}

}  // namespace breastfit::templ
