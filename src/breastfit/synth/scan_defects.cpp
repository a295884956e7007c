#include "breastfit/synth/scan_defects.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "breastfit/mesh/boundary.h"

namespace breastfit::synth {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

Vec3 row3(const Points& P, Index i) { return P.row(i).transpose(); }

Vec3 random_unit(Rng& rng) {
  for (;;) {
    const Vec3 v(rng.normal(), rng.normal(), rng.normal());
    if (v.norm() > 1e-6) return v.normalized();
  }
}

/// Two unit vectors completing n to an orthonormal basis.
void tangent_basis(const Vec3& n, Vec3& t1, Vec3& t2) {
  const Vec3 a = std::abs(n.x()) < 0.8 ? Vec3::UnitX() : Vec3::UnitY();
  t1 = n.cross(a).normalized();
  t2 = n.cross(t1).normalized();
}

/// Regular grid of quads (two triangles each) over the cells accepted by `keep`, lifted by `place`.
template <class Keep, class Place>
TriangleMesh grid_patch(int nx, int ny, Keep keep, Place place) {
  TriangleMesh m;
  std::vector<Index> id(static_cast<size_t>((nx + 1) * (ny + 1)), -1);
  std::vector<Vec3> verts;
  std::vector<std::array<Index, 3>> faces;
  auto vid = [&](int i, int j) {
    Index& r = id[static_cast<size_t>(j * (nx + 1) + i)];
    if (r < 0) {
      r = static_cast<Index>(verts.size());
      verts.push_back(place(i, j));
    }
    return r;
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (!keep(i, j)) continue;
      const Index a = vid(i, j), b = vid(i + 1, j), c = vid(i + 1, j + 1), d = vid(i, j + 1);
      faces.push_back({a, b, c});
      faces.push_back({a, c, d});
    }
  m.V.resize(static_cast<Index>(verts.size()), 3);
  for (size_t i = 0; i < verts.size(); ++i) m.V.row(static_cast<Index>(i)) = verts[i].transpose();
  m.F.resize(static_cast<Index>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) m.F.row(static_cast<Index>(i)) << faces[i][0], faces[i][1], faces[i][2];
  return m;
}

}  // namespace

void append_mesh(TriangleMesh& a, const TriangleMesh& b) {
  const Index nv = a.num_vertices(), nf = a.num_faces();
  a.V.conservativeResize(nv + b.num_vertices(), 3);
  a.V.bottomRows(b.num_vertices()) = b.V;
  a.F.conservativeResize(nf + b.num_faces(), 3);
  a.F.bottomRows(b.num_faces()) = b.F.array() + nv;
  a.N.resize(0, 3);
  a.C.resize(0, 3);
}

std::vector<Hole> punch_holes(TriangleMesh& scan, const std::vector<Vec3>& keep_clear, const ArtifactOptions& o,
                              Rng& rng) {
  std::vector<Hole> holes;
  const Index nv = scan.num_vertices();
  if (o.n_holes == 0 || nv == 0 || scan.num_faces() == 0) return holes;
  const std::vector<bool> on_border = mesh::boundary_vertices(scan);
  std::vector<bool> used(static_cast<size_t>(nv), false);
  for (Index f = 0; f < scan.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) used[static_cast<size_t>(scan.F(f, k))] = true;
  std::vector<Vec3> border;
  for (Index v = 0; v < nv; ++v)
    if (on_border[static_cast<size_t>(v)]) border.push_back(row3(scan.V, v));

  for (int attempt = 0; attempt < 400 && static_cast<int>(holes.size()) < o.n_holes; ++attempt) {
    const Index v = static_cast<Index>(rng.below(static_cast<std::uint64_t>(nv)));
    const double r = rng.uniform(o.hole_radius_mm.lo, o.hole_radius_mm.hi);
    if (!used[static_cast<size_t>(v)]) continue;
    const Vec3 c = row3(scan.V, v);
    bool ok = true;
    for (const Vec3& l : keep_clear)
      if ((l - c).norm() < o.hole_landmark_clearance_mm + r) ok = false;
    for (const Hole& h : holes)
      if ((h.centre - c).norm() < h.radius_mm + r + 10.0) ok = false;
    if (!ok) continue;
    for (const Vec3& b : border)
      if ((b - c).squaredNorm() < (r + 6.0) * (r + 6.0)) {
        ok = false;
        break;
      }
    if (ok) holes.push_back({c, r});
  }
  if (holes.empty()) return holes;

  Index kept = 0;
  for (Index f = 0; f < scan.num_faces(); ++f) {
    bool inside = false;
    for (int k = 0; k < 3 && !inside; ++k) {
      const Vec3 p = row3(scan.V, scan.F(f, k));
      for (const Hole& h : holes)
        if ((p - h.centre).squaredNorm() <= h.radius_mm * h.radius_mm) inside = true;
    }
    if (!inside) scan.F.row(kept++) = scan.F.row(f);
  }
  scan.F.conservativeResize(kept, 3);
  return holes;
}

void add_scan_noise(Points& V, const Points& N, const ArtifactOptions& o, Rng& rng) {
  constexpr int kWaves = 6;
  struct Wave {
    Vec3 k;
    double phase;
  };
  Wave waves[kWaves];
  for (auto& w : waves) {
    const double lambda = rng.uniform(o.lowfreq_wavelength_mm.lo, o.lowfreq_wavelength_mm.hi);
    w.k = random_unit(rng) * (kTwoPi / lambda);
    w.phase = rng.uniform(0.0, kTwoPi);
  }
  const double wave_amp = o.lowfreq_noise_mm * std::sqrt(2.0 / kWaves);  // RMS of the sum = lowfreq_noise_mm
  for (Index i = 0; i < V.rows(); ++i) {
    const Vec3 n = row3(N, i);
    const Vec3 p = row3(V, i);
    double smooth = 0.0;
    for (const auto& w : waves) smooth += std::sin(w.k.dot(p) + w.phase);
    const double along = wave_amp * smooth + o.white_noise_mm * rng.normal();
    Vec3 t1, t2;
    tangent_basis(n.squaredNorm() > 0.5 ? n : Vec3::UnitZ(), t1, t2);
    const double j1 = o.tangential_jitter_mm * rng.normal(), j2 = o.tangential_jitter_mm * rng.normal();
    V.row(i) = (p + along * n + j1 * t1 + j2 * t2).transpose();
  }
}

TriangleMesh make_fragments(const TriangleMesh& scan, const Points& N, const ArtifactOptions& o, Rng& rng,
                            std::vector<Fragment>& fragments) {
  TriangleMesh out;
  out.V.resize(0, 3);
  out.F.resize(0, 3);
  if (scan.num_faces() == 0) return out;
  for (int k = 0; k < o.n_fragments; ++k) {
    const Index f = static_cast<Index>(rng.below(static_cast<std::uint64_t>(scan.num_faces())));
    const Index v = scan.F(f, 0);
    const Vec3 p = row3(scan.V, v);
    Vec3 n = row3(N, v);
    if (n.squaredNorm() < 0.5) n = Vec3::UnitZ();
    const double dist = rng.uniform(o.fragment_distance_mm.lo, o.fragment_distance_mm.hi);
    const double radius = rng.uniform(o.fragment_radius_mm.lo, o.fragment_radius_mm.hi);
    const Vec3 tilt = random_unit(rng);
    const double curvature = rng.uniform(-0.01, 0.01);  // 1/mm
    const Vec3 axis = (n + 0.4 * tilt).normalized();
    const Vec3 c = p + dist * n;
    Vec3 u, w;
    tangent_basis(axis, u, w);  // u x w = axis
    const double h = 3.0;
    const int cells = std::max(2, static_cast<int>(std::ceil(2.0 * radius / h)));
    const double step = 2.0 * radius / cells;
    auto xy = [&](double i, double j) { return Vec2(-radius + i * step, -radius + j * step); };
    TriangleMesh patch = grid_patch(
        cells, cells, [&](int i, int j) { return xy(i + 0.5, j + 0.5).norm() <= radius; },
        [&](int i, int j) {
          const Vec2 q = xy(i, j);
          return Vec3(c + q.x() * u + q.y() * w + curvature * q.squaredNorm() * axis);
        });
    // grid_patch triangles turn counter-clockwise in (u, w): normal along u x w.
    if (u.cross(w).dot(axis) < 0) patch.F.col(1).swap(patch.F.col(2));
    append_mesh(out, patch);
    fragments.push_back({c, radius, dist});
  }
  return out;
}

TriangleMesh make_table_strips(const Points& body, Rng& rng) {
  TriangleMesh out;
  out.V.resize(0, 3);
  out.F.resize(0, 3);
  if (body.rows() == 0) return out;
  const double y_table = body.col(1).maxCoeff() + 2.0;
  const double z_lo = body.col(2).minCoeff(), z_hi = body.col(2).maxCoeff();
  const double z_top = z_lo + 0.45 * (z_hi - z_lo);
  double x_min = std::numeric_limits<double>::max(), x_max = -x_min;
  for (Index i = 0; i < body.rows(); ++i)
    if (body(i, 2) <= z_top + 20.0) {
      x_min = std::min(x_min, body(i, 0));
      x_max = std::max(x_max, body(i, 0));
    }
  const double h = 5.0;
  for (int side = 0; side < 2; ++side) {
    const double gap = rng.uniform(10.0, 30.0);
    const double width = rng.uniform(40.0, 80.0);
    const double x0 = side == 0 ? x_min - gap - width : x_max + gap;
    const int nx = std::max(1, static_cast<int>(std::round(width / h)));
    const int nz = std::max(1, static_cast<int>(std::round((z_top - z_lo) / h)));
    const double hx = width / nx, hz = (z_top - z_lo) / nz;
    // (x, z) counter-clockwise seen from -y: corners (i,j),(i+1,j),(i+1,j+1) give normal -y.
    TriangleMesh strip = grid_patch(
        nx, nz, [](int, int) { return true; },
        [&](int i, int j) { return Vec3(x0 + i * hx, y_table, z_lo + j * hz); });
    append_mesh(out, strip);
  }
  return out;
}

}  // namespace breastfit::synth
