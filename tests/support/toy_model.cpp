#include "support/toy_model.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "breastfit/core/rng.h"
#include "breastfit/model/gltf_io.h"
#include "breastfit/model/pose_evaluator.h"

namespace breastfit::test {
namespace {

constexpr int kSectors = 24;
constexpr int kRings = 17;          // rings of vertices along z
constexpr double kHeight = 240.0;   // mm
constexpr double kRadiusX = 60.0;   // mm, left-right half width
constexpr double kRadiusY = 40.0;   // mm, antero-posterior half depth
constexpr double kPi = std::numbers::pi;

double ring_z(int k) { return kHeight * k / (kRings - 1); }
double sector_theta(double t) { return 2.0 * kPi * t / kSectors; }
Index grid_vertex(int k, int t) { return static_cast<Index>(k * kSectors + ((t % kSectors) + kSectors) % kSectors); }
Vec3 surface_at(double theta, double z) { return {kRadiusX * std::cos(theta), kRadiusY * std::sin(theta), z}; }

Mat3 axis_angle(double angle, const Vec3& axis) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

/// The surface point at grid parameters (t in sectors, k in rings), t ∈ [0, 24), k ∈ [0, 16).
SurfacePoint grid_point(double t, double k) {
  const int ti = static_cast<int>(std::floor(t));
  const int ki = std::clamp(static_cast<int>(std::floor(k)), 0, kRings - 2);
  const double u = t - ti, v = k - ki;
  const Index quad = static_cast<Index>(ki * kSectors + (ti % kSectors));
  SurfacePoint p;
  if (u >= v) {  // triangle (v00, v01, v11)
    p.face = 2 * quad;
    p.bary = Vec3(1 - u, u - v, v);
  } else {  // triangle (v00, v11, v10)
    p.face = 2 * quad + 1;
    p.bary = Vec3(1 - v, u, v - u);
  }
  return p;
}

/// A localised bump: vertices within `radius` of the surface point at (theta, z).
model::Blendshape bump(const std::string& name, const Points& V, double theta, double z, double radius,
                       const Vec3& direction, double lo, double hi) {
  model::Blendshape s;
  s.name = name;
  s.lo = lo;
  s.hi = hi;
  const Vec3 c = surface_at(theta, z);
  std::vector<Vec3> d;
  for (Index i = 0; i < V.rows(); ++i) {
    const double r = (V.row(i).transpose() - c).norm() / radius;
    if (r >= 1.0) continue;
    const double f = (1 - r * r) * (1 - r * r);
    const Vec3 radial = Vec3(V(i, 0), V(i, 1), 0).normalized();
    s.vertices.push_back(i);
    d.push_back(f * (direction + 0.3 * std::sin(3.0 * i) * radial));
  }
  s.displacements.resize(static_cast<Index>(d.size()), 3);
  for (size_t r = 0; r < d.size(); ++r) s.displacements.row(static_cast<Index>(r)) = d[r].transpose();
  return s;
}

model::Blendshape global_shape(const std::string& name, const Points& V, double lo, double hi,
                               Vec3 (*fn)(const Vec3&)) {
  model::Blendshape s;
  s.name = name;
  s.lo = lo;
  s.hi = hi;
  std::vector<Vec3> d;
  for (Index i = 0; i < V.rows(); ++i) {
    const Vec3 disp = fn(V.row(i).transpose());
    if (disp.squaredNorm() == 0.0) continue;
    s.vertices.push_back(i);
    d.push_back(disp);
  }
  s.displacements.resize(static_cast<Index>(d.size()), 3);
  for (size_t r = 0; r < d.size(); ++r) s.displacements.row(static_cast<Index>(r)) = d[r].transpose();
  return s;
}

}  // namespace

model::RiggedModel make_toy_model() {
  model::RiggedModel m;
  m.name = "toy";
  const Index n_grid = kRings * kSectors;
  const Index bottom = n_grid, top = n_grid + 1;
  Points V(n_grid + 2, 3);
  for (int k = 0; k < kRings; ++k)
    for (int t = 0; t < kSectors; ++t) V.row(grid_vertex(k, t)) = surface_at(sector_theta(t), ring_z(k)).transpose();
  V.row(bottom) = Vec3(0, 0, 0).transpose();
  V.row(top) = Vec3(0, 0, kHeight).transpose();

  std::vector<Eigen::Vector3i> tris;
  for (int k = 0; k + 1 < kRings; ++k) {
    for (int t = 0; t < kSectors; ++t) {
      const Index v00 = grid_vertex(k, t), v01 = grid_vertex(k, t + 1), v10 = grid_vertex(k + 1, t),
                  v11 = grid_vertex(k + 1, t + 1);
      tris.emplace_back(v00, v01, v11);
      tris.emplace_back(v00, v11, v10);
    }
  }
  for (int t = 0; t < kSectors; ++t) {
    tris.emplace_back(bottom, grid_vertex(0, t + 1), grid_vertex(0, t));
    tris.emplace_back(top, grid_vertex(kRings - 1, t), grid_vertex(kRings - 1, t + 1));
  }
  m.rest.V = V;
  m.rest.F.resize(static_cast<Index>(tris.size()), 3);
  for (size_t f = 0; f < tris.size(); ++f) m.rest.F.row(static_cast<Index>(f)) = tris[f].transpose();

  // Bones: a chain along the axis with tilted rest axes.
  struct BoneSpec {
    const char* name;
    double z;       // pivot height
    double centre;  // weight centre
    Mat3 axes;
    Vec3 lo, hi;
  };
  const BoneSpec specs[4] = {
      {"pelvis", 30, 40, axis_angle(0.3, Vec3(1, 2, 3)), Vec3(0.6, 0.7, 0.5), Vec3(1.5, 1.8, 1.6)},
      {"spine", 80, 115, axis_angle(0.5, Vec3(-1, 1, 0.5)), Vec3(0.5, 0.6, 0.7), Vec3(1.7, 1.4, 1.5)},
      {"chest", 150, 180, axis_angle(0.7, Vec3(0.2, -0.4, 1)), Vec3(0.7, 0.5, 0.6), Vec3(1.4, 1.6, 1.9)},
      {"neck", 210, 225, axis_angle(-0.4, Vec3(1, 0, 0)), Vec3(0.8, 0.8, 0.8), Vec3(1.3, 1.3, 1.3)},
  };
  for (int j = 0; j < 4; ++j) {
    model::Bone b;
    b.name = specs[j].name;
    if (j > 0) b.parent = j - 1;
    b.pivot = Vec3(0, j == 3 ? 5.0 : 0.0, specs[j].z);
    b.axes = specs[j].axes;
    b.scale_lo = specs[j].lo;
    b.scale_hi = specs[j].hi;
    m.bones.push_back(b);
  }

  // Smooth weights: Gaussian in height modulated around the circumference, top 3 kept.
  std::vector<Eigen::Triplet<double, Index>> trips;
  for (Index i = 0; i < V.rows(); ++i) {
    const double theta = std::atan2(V(i, 1), V(i, 0));
    const bool is_cap_centre = (i >= n_grid);
    std::array<std::pair<double, int>, 4> raw;
    for (int j = 0; j < 4; ++j) {
      const double g = std::exp(-std::pow((V(i, 2) - specs[j].centre) / 35.0, 2));
      raw[j] = {g * (is_cap_centre ? 1.0 : 1.0 + 0.3 * std::sin(theta + j)) + 1e-9, j};
    }
    std::sort(raw.begin(), raw.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    const double sum = raw[0].first + raw[1].first + raw[2].first;
    for (int r = 0; r < 3; ++r) trips.emplace_back(i, raw[r].second, raw[r].first / sum);
  }
  m.weights.resize(V.rows(), 4);
  m.weights.setFromTriplets(trips.begin(), trips.end());
  m.weights.makeCompressed();

  // Blendshapes.
  m.blendshapes.push_back(global_shape("bulge", V, -1.0, 1.0, [](const Vec3& p) -> Vec3 {
    const double r = std::hypot(p.x(), p.y());
    if (r == 0.0) return Vec3::Zero();
    return Vec3(p.x(), p.y(), 0) / r * 5.0 * std::sin(kPi * p.z() / kHeight);
  }));
  m.blendshapes.push_back(global_shape("taper", V, 0.0, 1.5, [](const Vec3& p) -> Vec3 {
    return Vec3(p.x(), p.y(), 0) * 0.2 * (p.z() / kHeight - 0.5);
  }));
  m.blendshapes.push_back(global_shape("twist", V, -2.0, 2.0, [](const Vec3& p) -> Vec3 {
    return Vec3(-p.y(), p.x(), 0.05 * p.x()) * 0.1 * p.z() / kHeight;
  }));
  const double t_breast_R = 15.5, t_breast_L = 20.5, k_breast = 10.0;  // grid parameters
  m.blendshapes.push_back(bump("breast_R", V, sector_theta(t_breast_R), ring_z(0) + k_breast * kHeight / (kRings - 1),
                               45.0, Vec3(-2.0, -12.0, -3.0), 0.0, 1.0));
  m.blendshapes.push_back(bump("breast_L", V, sector_theta(t_breast_L), k_breast * kHeight / (kRings - 1), 45.0,
                               Vec3(2.0, -12.0, -3.0), -0.5, 1.0));
  m.blendshapes.push_back(bump("dent", V, sector_theta(6.0), 100.0, 40.0, Vec3(0.0, -6.0, 1.5), -1.0, 0.5));

  // Landmarks.
  m.landmarks.push_back({"sternal_notch", grid_point(18.0 + 0.25, 14.5)});
  m.landmarks.push_back({"nipple_R", grid_point(t_breast_R + 0.1, k_breast + 0.3)});
  m.landmarks.push_back({"nipple_L", grid_point(t_breast_L - 0.2, k_breast + 0.1)});

  // Drawings.
  model::Drawing sternum{"sternum", false, {}};
  for (int s = 0; s <= 20; ++s) sternum.points.push_back(grid_point(18.0 + 0.05 * std::sin(s), 4.0 + 0.5 * s));
  m.drawings.push_back(sternum);
  model::Drawing contour{"breast_contour_R", true, {}};
  for (int s = 0; s < 16; ++s) {
    const double phi = 2 * kPi * s / 16;
    contour.points.push_back(grid_point(t_breast_R + 2.2 * std::cos(phi), k_breast + 2.6 * std::sin(phi)));
  }
  m.drawings.push_back(contour);

  // Region.
  m.regions.push_back({"breast_R", m.blendshapes[3].vertices});
  return m;
}

model::PoseParams random_toy_pose(const model::RiggedModel& model, std::uint64_t seed, double amplitude) {
  Rng rng(seed);
  auto unit = [&rng] { return Vec3(rng.normal(), rng.normal(), rng.normal()).normalized(); };
  model::PoseParams p = model::PoseParams::identity(model);
  p.global.rotation = Quat(Eigen::AngleAxisd(rng.uniform(0.05, 0.3), unit()));
  p.global.translation = Vec3(rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-20, 20));
  p.global.scale = rng.uniform(0.9, 1.1);
  for (int j = 0; j < model.num_bones(); ++j) {
    const auto& b = model.bones[j];
    auto& bp = p.bones[j];
    bp.rotation = Quat(Eigen::AngleAxisd(amplitude * rng.uniform(0.02, 0.25), unit()));
    bp.translation = amplitude * 4.0 * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    for (int a = 0; a < 3; ++a) {
      const double lo = 1.0 + amplitude * (b.scale_lo[a] - 1.0), hi = 1.0 + amplitude * (b.scale_hi[a] - 1.0);
      bp.scale[a] = rng.uniform(lo, hi);
    }
  }
  for (int k = 0; k < model.num_blendshapes(); ++k) {
    const auto& s = model.blendshapes[k];
    const double rest = std::clamp(0.0, s.lo, s.hi);
    p.alpha[k] = rng.uniform(rest + amplitude * (s.lo - rest), rest + amplitude * (s.hi - rest));
  }
  return p;
}

ToyScanCase::ToyScanCase(std::uint64_t seed, double amplitude)
    : m(make_toy_model()), truth(random_toy_pose(m, seed, amplitude)) {
  mesh.V = model::pose_vertices(m, truth);
  mesh.F = m.rest.F;
}

std::vector<std::pair<std::string, Vec3>> ToyScanCase::named_landmarks() const {
  std::vector<std::pair<std::string, Vec3>> named;
  for (const auto& lm : m.landmarks) named.emplace_back(lm.name, lm.point.position(mesh.V, m.rest.F));
  return named;
}

}  // namespace breastfit::test

namespace breastfit::test {

std::filesystem::path save_two_mesh_toy(const std::filesystem::path& dir) {
  const std::filesystem::path one = dir / "one.gltf", two = dir / "two.gltf";
  model::save_gltf(one, make_toy_model());
  nlohmann::json j = nlohmann::json::parse(std::ifstream(one));
  auto second = j["nodes"][0];
  second["name"] = "Second";
  j["nodes"][0]["name"] = "First";
  j["nodes"].push_back(second);
  j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
  std::ofstream(two) << j.dump();
  return two;
}

}  // namespace breastfit::test
