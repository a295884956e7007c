#include "breastfit/transfer/drawing_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/spatial/knn_index.h"
#include "breastfit/transfer/polyline.h"

namespace breastfit::transfer {
namespace fs = std::filesystem;
namespace {

void check_factor(double from_mm) {
  if (!(from_mm > 0) || !std::isfinite(from_mm))
    throw InvalidInput("drawing outputs: from_mm must be > 0 (got " + std::to_string(from_mm) + ")");
}

std::ofstream open_out(const fs::path& path) {
  std::ofstream f(path);
  if (!f) throw IoError(path.string(), "cannot open for writing");
  return f;
}

void finish(std::ofstream& f, const fs::path& path) {
  f.flush();
  if (!f) throw IoError(path.string(), "write failed (disk full?)");
}

// One vertex line of the drawings' text meshes, as `format` says ("%.9g" per coordinate, then
// the rest): one formatting call per line instead of a string and a stream insertion per value.
template <class... Rest>
void write_vertex_line(std::ofstream& f, const char* format, const Points& p, Eigen::Index i, double from_mm,
                       Rest... rest) {
  char buf[160];
  const int n = std::snprintf(buf, sizeof buf, format, p(i, 0) * from_mm, p(i, 1) * from_mm, p(i, 2) * from_mm, rest...);
  f.write(buf, std::min<std::streamsize>(n, sizeof buf - 1));
}

// The cells of a coarse grid that can hold a point within `reach` of a sample: a cell is marked
// when it overlaps a sample's box [s − reach, s + reach]. A scan vertex in no marked cell is
// skin without a nearest-sample query (exact: the painting is the same, most of the scan is far
// from every drawing).
class ReachCells {
 public:
  ReachCells(const Points& samples, double reach) {
    lo_ = samples.colwise().minCoeff().transpose() - Vec3::Constant(reach);
    const Vec3 hi = samples.colwise().maxCoeff().transpose() + Vec3::Constant(reach);
    cell_ = std::max(8.0 * reach, 1e-9);
    for (;;) {  // at most ~2M cells
      for (int a = 0; a < 3; ++a) dims_[a] = static_cast<Index>(std::floor((hi[a] - lo_[a]) / cell_)) + 1;
      if (dims_[0] * dims_[1] * dims_[2] <= (Index{1} << 21)) break;
      cell_ *= 2;
    }
    marked_.assign(static_cast<size_t>(dims_[0] * dims_[1] * dims_[2]), 0);
    for (Index i = 0; i < samples.rows(); ++i) {
      Index from[3], to[3];
      for (int a = 0; a < 3; ++a) {
        from[a] = cell(samples(i, a) - reach, a);
        to[a] = cell(samples(i, a) + reach, a);
      }
      for (Index x = from[0]; x <= to[0]; ++x)
        for (Index y = from[1]; y <= to[1]; ++y)
          for (Index z = from[2]; z <= to[2]; ++z) marked_[static_cast<size_t>((x * dims_[1] + y) * dims_[2] + z)] = 1;
    }
  }

  /// False when no sample is within `reach` of q.
  bool may_reach(const Vec3& q) const {
    Index c[3];
    for (int a = 0; a < 3; ++a) {
      const double t = std::floor((q[a] - lo_[a]) / cell_);
      if (!(t >= 0 && t < static_cast<double>(dims_[a]))) return false;
      c[a] = static_cast<Index>(t);
    }
    return marked_[static_cast<size_t>((c[0] * dims_[1] + c[1]) * dims_[2] + c[2])] != 0;
  }

 private:
  // Cell of coordinate x along axis a, clamped to the grid (x within the samples' box ± reach).
  Index cell(double x, int a) const {
    const double t = std::floor((x - lo_[a]) / cell_);
    return std::clamp(static_cast<Index>(t), Index{0}, dims_[a] - 1);
  }

  Vec3 lo_;
  double cell_ = 1;
  Index dims_[3] = {1, 1, 1};
  std::vector<unsigned char> marked_;
};

// Names may not contain spaces in a PLY comment / OBJ object line.
std::string token(const std::string& name) {
  std::string t = name.empty() ? "curve" : name;
  for (char& ch : t)
    if (ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r') ch = '_';
  return t;
}

}  // namespace

Rgb drawing_color(const std::string& name, size_t index) { return mesh::drawing_colour(name, index); }

void write_drawings_ply(const fs::path& path, const std::vector<TransferredCurve>& curves, double from_mm) {
  check_factor(from_mm);
  Eigen::Index nv = 0, ne = 0;
  for (const auto& c : curves) {
    const Eigen::Index n = c.points.rows();
    nv += n;
    ne += n < 2 ? 0 : (c.closed && n > 2 ? n : n - 1);
  }
  std::ofstream f = open_out(path);
  f << "ply\nformat ascii 1.0\ncomment breastfit transferred drawings (polylines)\n";
  Eigen::Index first = 0;
  for (const auto& c : curves) {
    f << "comment curve " << token(c.name) << " " << first << " " << c.points.rows() << " "
      << (c.closed ? "closed" : "open") << "\n";
    first += c.points.rows();
  }
  f << "element vertex " << nv << "\nproperty double x\nproperty double y\nproperty double z\n"
    << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    << "element edge " << ne << "\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  for (size_t k = 0; k < curves.size(); ++k) {
    const auto& c = curves[k];
    const Rgb col = drawing_color(c.name, k);
    for (Eigen::Index i = 0; i < c.points.rows(); ++i)
      write_vertex_line(f, "%.9g %.9g %.9g %d %d %d\n", c.points, i, from_mm, int(col[0]), int(col[1]), int(col[2]));
  }
  first = 0;
  for (const auto& c : curves) {
    const Eigen::Index n = c.points.rows();
    for (Eigen::Index i = 0; i + 1 < n; ++i) f << first + i << " " << first + i + 1 << "\n";
    if (c.closed && n > 2) f << first + n - 1 << " " << first << "\n";
    first += n;
  }
  finish(f, path);
}

void write_drawings_obj(const fs::path& path, const std::vector<TransferredCurve>& curves, double from_mm) {
  check_factor(from_mm);
  std::ofstream f = open_out(path);
  f << "# breastfit transferred drawings (polylines)\n";
  for (const auto& c : curves)
    for (Eigen::Index i = 0; i < c.points.rows(); ++i)
      write_vertex_line(f, "v %.9g %.9g %.9g\n", c.points, i, from_mm);
  Eigen::Index first = 1;  // OBJ indices are 1-based
  for (const auto& c : curves) {
    const Eigen::Index n = c.points.rows();
    f << "o " << token(c.name) << "\n";
    if (n >= 2) {
      f << "l";
      for (Eigen::Index i = 0; i < n; ++i) f << " " << first + i;
      if (c.closed && n > 2) f << " " << first;
      f << "\n";
    }
    first += n;
  }
  finish(f, path);
}

Colors paint_colors(const TriangleMesh& scan_mm, const std::vector<TransferredCurve>& curves,
                    const PaintOptions& options) {
  if (!(options.width_mm > 0) || !std::isfinite(options.width_mm))
    throw InvalidInput("PaintOptions.width_mm must be > 0 (got " + std::to_string(options.width_mm) + ")");
  Colors out(scan_mm.V.rows(), 3);
  for (Eigen::Index v = 0; v < out.rows(); ++v) out.row(v) << options.skin[0], options.skin[1], options.skin[2];
  // Dense samples of every curve (spacing well below the band width), indexed once.
  const double half = 0.5 * options.width_mm;
  const double spacing = std::min(0.5, half);
  std::vector<Points> samples;
  std::vector<int> owner;
  Eigen::Index total = 0;
  for (size_t k = 0; k < curves.size(); ++k) {
    if (curves[k].points.rows() == 0) continue;
    samples.push_back(resample_polyline(curves[k].points, curves[k].closed, spacing));
    owner.insert(owner.end(), static_cast<size_t>(samples.back().rows()), static_cast<int>(k));
    total += samples.back().rows();
  }
  if (total == 0 || scan_mm.V.rows() == 0) return out;
  Points all(total, 3);
  Eigen::Index r = 0;
  for (const auto& s : samples) {
    all.middleRows(r, s.rows()) = s;
    r += s.rows();
  }
  const spatial::KnnIndex index(all);
  // A vertex within `half` of the polyline is within half + spacing/2 of a sample.
  const double reach = half + 0.5 * spacing;
  const ReachCells cells(all, reach);
  // Where bands overlap (e.g. a fold drawn along the contour) the later curve is painted on top.
  std::vector<Index> near;
  std::vector<double> sq;
  for (Eigen::Index v = 0; v < scan_mm.V.rows(); ++v) {
    const Vec3 q = scan_mm.V.row(v).transpose();
    if (!cells.may_reach(q) || index.closest(q).sq_dist > reach * reach) continue;
    index.radius_search(q, reach, near, sq);
    int top = -1;
    for (Index i : near) top = std::max(top, owner[static_cast<size_t>(i)]);
    if (top < 0) continue;
    const Rgb col = drawing_color(curves[static_cast<size_t>(top)].name, static_cast<size_t>(top));
    out.row(v) << col[0], col[1], col[2];
  }
  return out;
}

TriangleMesh paint_drawings(const TriangleMesh& scan_mm, const std::vector<TransferredCurve>& curves,
                            const PaintOptions& options) {
  Colors colors = paint_colors(scan_mm, curves, options);
  TriangleMesh out = scan_mm;
  out.C = std::move(colors);
  return out;
}

void write_scan_painted(const fs::path& path, const TriangleMesh& scan_mm, const std::vector<TransferredCurve>& curves,
                        double from_mm, const PaintOptions& options) {
  check_factor(from_mm);
  // The painted copy without the normals (not written) and with the vertices scaled as they are
  // copied: one pass over the scan's arrays instead of a full copy, a scaling and a release.
  TriangleMesh painted;
  painted.C = paint_colors(scan_mm, curves, options);
  painted.V = scan_mm.V * from_mm;
  painted.F = scan_mm.F;
  painted.UV = scan_mm.UV;
  painted.FUV = scan_mm.FUV;
  io::MeshWriteOptions wo;
  wo.colors = true;
  io::write_mesh(path, painted, wo);
}

}  // namespace breastfit::transfer
