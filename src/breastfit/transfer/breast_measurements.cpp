#include "breastfit/transfer/breast_measurements.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "breastfit/core/errors.h"
#include "breastfit/core/task_queue.h"
#include "breastfit/mesh/adjacency.h"
#include "breastfit/mesh/graph.h"
#include "breastfit/transfer/curve_region.h"
#include "breastfit/transfer/volume_cache.h"

namespace breastfit::transfer {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

double signed_volume6(const Points& V, const Triangles& F) {
  double s = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Vec3 a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    s += a.dot(b.cross(c));
  }
  return s;
}

std::optional<double> ratio(const std::optional<double>& l, const std::optional<double>& r) {
  if (!l || !r || std::abs(*r) < 1e-12) return std::nullopt;
  return *l / *r;
}

}  // namespace

void VolumeOptions::validate() const {
  if (!(margin_mm >= 0) || !std::isfinite(margin_mm))
    throw InvalidInput("VolumeOptions.margin_mm = " + std::to_string(margin_mm) + ": must be >= 0");
}

RegionVolume region_volume(const TriangleMesh& surface, const std::vector<Index>& region, const VolumeOptions& options,
                           VolumeCache* cache) {
  options.validate();
  const ChestWallFill fill = options.fill;
  const Index nv = surface.num_vertices();
  if (region.empty()) throw InvalidInput("region_volume: empty region");
  for (const Index v : region)
    if (v < 0 || v >= nv) throw InvalidInput("region_volume: vertex index " + std::to_string(v) + " out of range");
  const std::shared_ptr<const MeshTopology> topology = topology_of(surface, cache);
  const mesh::AdjacencyLists& nbr = topology->neighbours;
  // Grown region: Dijkstra along edges from the region, up to margin_mm.
  const std::vector<double> dist = mesh::edge_distances(surface.V, nbr, region, options.margin_mm);
  std::vector<int> slot(static_cast<size_t>(nv), -1);
  int n_in = 0;
  for (Index v = 0; v < nv; ++v)
    if (std::isfinite(dist[static_cast<size_t>(v)])) slot[static_cast<size_t>(v)] = n_in++;
  if (n_in >= nv) throw InvalidInput("region_volume: the region (with its margin) covers the whole mesh (no chest wall around it)");

  // Split M into free (region) / fixed columns for the rows of the region: Mii and the fixed
  // columns' part moved to the right-hand side.
  std::vector<Eigen::Triplet<double>> tii;
  Points rhs = Points::Zero(n_in, 3);
  if (fill == ChestWallFill::ThinPlate) {
    // Uniform graph Laplacian L (symmetric: L = D − A over the mesh edges); thin plate: minimise
    // ‖L x‖² → Lᵀ L x = 0 on the region's rows.
    std::vector<Eigen::Triplet<double>> t;
    for (Index v = 0; v < nv; ++v) {
      t.emplace_back(v, v, static_cast<double>(nbr.size(v)));
      for (const Index w : nbr[v]) t.emplace_back(v, w, -1.0);
    }
    SpMat L(nv, nv);
    L.setFromTriplets(t.begin(), t.end());
    const SpMat M = SpMat(SpMat(L.transpose()) * L);
    for (int k = 0; k < M.outerSize(); ++k)
      for (SpMat::InnerIterator it(M, k); it; ++it) {
        const int r = slot[static_cast<size_t>(it.row())];
        if (r < 0) continue;
        const int c = slot[static_cast<size_t>(it.col())];
        if (c >= 0) tii.emplace_back(r, c, it.value());
        else rhs.row(r) -= it.value() * surface.V.row(it.col());
      }
  } else {
    // Membrane: L x = 0 on the region's rows, read from the neighbour lists of the region alone
    // (the entries of L's rows, fixed columns in ascending order as in a pass over L's columns).
    for (Index v = 0; v < nv; ++v) {
      const int r = slot[static_cast<size_t>(v)];
      if (r < 0) continue;
      tii.emplace_back(r, r, static_cast<double>(nbr.size(v)));
      for (const Index w : nbr[v]) {
        const int c = slot[static_cast<size_t>(w)];
        if (c >= 0) tii.emplace_back(r, c, -1.0);
        else rhs.row(r) += surface.V.row(w);  // −(−1) · x_w
      }
    }
  }
  SpMat Mii(n_in, n_in);
  Mii.setFromTriplets(tii.begin(), tii.end());
  const std::shared_ptr<const FillSolver> factorized = cache ? cache->fill_solver(Mii) : std::make_shared<const FillSolver>(Mii);
  const FillSolver& solver = *factorized;
  if (solver.info() != Eigen::Success)
    throw InvalidInput("region_volume: singular chest-wall fill (is the region attached to the rest of the mesh?)");
  RegionVolume out;
  out.chest_wall = surface.V;
  for (int c = 0; c < 3; ++c) {
    const Eigen::VectorXd x = solver.solve(rhs.col(c));
    if (solver.info() != Eigen::Success || !x.allFinite())
      throw InvalidInput("region_volume: the chest-wall fill failed to solve");
    for (Index v = 0; v < nv; ++v)
      if (slot[static_cast<size_t>(v)] >= 0) out.chest_wall(v, c) = x[slot[static_cast<size_t>(v)]];
  }
  // Only faces touching the region differ between skin and fill.
  std::vector<Index> faces;
  for (Index f = 0; f < surface.num_faces(); ++f)
    if (slot[static_cast<size_t>(surface.F(f, 0))] >= 0 || slot[static_cast<size_t>(surface.F(f, 1))] >= 0 ||
        slot[static_cast<size_t>(surface.F(f, 2))] >= 0)
      faces.push_back(f);
  Triangles Fr(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) Fr.row(static_cast<Eigen::Index>(i)) = surface.F.row(faces[i]);
  out.volume_mm3 = (signed_volume6(surface.V, Fr) - signed_volume6(out.chest_wall, Fr)) / 6.0;
  return out;
}

namespace {

void check_posed(const model::RiggedModel& model, const Points& posed_mm) {
  if (posed_mm.rows() != model.num_vertices())
    throw InvalidInput("measure_breasts: " + std::to_string(posed_mm.rows()) + " posed vertices for a model with " +
                       std::to_string(model.num_vertices()));
}

std::optional<Vec3> posed_landmark(const model::RiggedModel& model, const Points& posed_mm, const std::string& name) {
  const auto i = model.landmark_index(name);
  if (!i) return std::nullopt;
  return model.landmarks[static_cast<size_t>(*i)].point.position(posed_mm, model.rest.F);
}

// Vertical: xiphoid → sternal_notch of the posed model, else +z (nullopt: the fallback).
std::optional<Vec3> posed_up(const model::RiggedModel& model, const Points& posed_mm) {
  const auto notch = posed_landmark(model, posed_mm, "sternal_notch");
  const auto xiphoid = posed_landmark(model, posed_mm, "xiphoid");
  if (notch && xiphoid && (*notch - *xiphoid).norm() > 1e-9) return (*notch - *xiphoid).normalized();
  return std::nullopt;
}

}  // namespace

BreastSideMeasurement measure_breast_side(const model::RiggedModel& model, const Points& posed_mm, char side,
                                          const VolumeOptions& options, VolumeCache* cache) {
  check_posed(model, posed_mm);
  if (side != 'R' && side != 'L') throw InvalidInput(std::string("measure_breast_side: side '") + side + "' (R or L)");
  const Triangles& F = model.rest.F;
  const Vec3 up = posed_up(model, posed_mm).value_or(Vec3(0, 0, 1));
  const auto notch = posed_landmark(model, posed_mm, "sternal_notch");
  BreastSideMeasurement out;
  std::vector<std::string>& warnings = out.warnings;
  BreastSide& b = out.numbers;
  const std::string s(1, side);
  const auto nipple = posed_landmark(model, posed_mm, "nipple_" + s);
  if (!nipple) warnings.push_back("landmark nipple_" + s + " missing");
  if (nipple && notch) b.notch_to_nipple_mm = (*nipple - *notch).norm();

  const model::Drawing* fold = nullptr;
  for (const std::string name : {"imf_" + s, "breast_contour_" + s}) {
    if (const auto i = model.drawing_index(name)) {
      fold = &model.drawings[static_cast<size_t>(*i)];
      break;
    }
  }
  if (fold && !fold->points.empty()) {
    Vec3 lowest = fold->points[0].position(posed_mm, F);
    for (const auto& p : fold->points) {
      const Vec3 x = p.position(posed_mm, F);
      if (x.dot(up) < lowest.dot(up)) lowest = x;
    }
    b.imf_lowest_mm = lowest;
    if (nipple) b.nipple_to_imf_mm = (*nipple - lowest).norm();
  } else {
    warnings.push_back("drawings imf_" + s + " and breast_contour_" + s + " missing");
  }

  // Volume: the skin inside the breast contour against a chest wall spanning the contour
  // (curve_region.h) — the same rule `breastfit volume` and the bench validation apply.
  const auto c = model.drawing_index("breast_contour_" + s);
  if (c && model.drawings[static_cast<size_t>(*c)].points.size() >= 3) {
    const auto& pts = model.drawings[static_cast<size_t>(*c)].points;
    Points curve(static_cast<Index>(pts.size()), 3);
    for (size_t i = 0; i < pts.size(); ++i) curve.row(static_cast<Index>(i)) = pts[i].position(posed_mm, F).transpose();
    TriangleMesh skin;
    skin.V = posed_mm;
    skin.F = F;
    try {
      CurveVolumeOptions co;
      co.volume = options;
      co.target_edge_mm = 4.0;  // within 0.5 % of finer refinements (docs/TRANSFER.md), 4x fewer faces than 2 mm
      b.volume_ml = curve_volume(skin, curve, co, cache).volume_ml;
      if (*b.volume_ml < 0) warnings.push_back("breast_" + s + " volume is negative (the skin lies under the chest-wall fill)");
    } catch (const InvalidInput& e) {
      warnings.push_back("breast_" + s + " volume not measured: " + e.what());
    }
  } else {
    warnings.push_back("drawing breast_contour_" + s + " missing: no volume");
  }
  return out;
}

BreastMeasurements join_breast_sides(const model::RiggedModel& model, const Points& posed_mm,
                                     BreastSideMeasurement right, BreastSideMeasurement left,
                                     const VolumeOptions& options) {
  check_posed(model, posed_mm);
  BreastMeasurements m;
  m.volume_options = options;
  if (!posed_up(model, posed_mm)) m.warnings.push_back("sternal_notch or xiphoid missing: 'lowest' uses the +z axis of the fit");
  m.right = std::move(right.numbers);
  m.left = std::move(left.numbers);
  for (auto* w : {&right.warnings, &left.warnings}) m.warnings.insert(m.warnings.end(), w->begin(), w->end());
  const auto nr = posed_landmark(model, posed_mm, "nipple_R"), nl = posed_landmark(model, posed_mm, "nipple_L");
  if (nr && nl) m.inter_nipple_mm = (*nr - *nl).norm();
  m.volume_ratio = ratio(m.left.volume_ml, m.right.volume_ml);
  m.notch_to_nipple_ratio = ratio(m.left.notch_to_nipple_mm, m.right.notch_to_nipple_mm);
  m.nipple_to_imf_ratio = ratio(m.left.nipple_to_imf_mm, m.right.nipple_to_imf_mm);
  return m;
}

BreastMeasurements measure_breasts(const model::RiggedModel& model, const Points& posed_mm, const VolumeOptions& options,
                                   VolumeCache* cache, unsigned threads) {
  check_posed(model, posed_mm);
  // The two sides are independent (each writes its own numbers and warnings, joined in order).
  BreastSideMeasurement sides[2];
  run_in_order(2, std::max(1u, threads), [&](std::size_t side) {
    sides[side] = measure_breast_side(model, posed_mm, side == 0 ? 'R' : 'L', options, cache);
  });
  return join_breast_sides(model, posed_mm, std::move(sides[0]), std::move(sides[1]), options);
}

}  // namespace breastfit::transfer
