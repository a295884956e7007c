#include "breastfit/template/template_mesh.h"

#include <cmath>

#include "breastfit/core/errors.h"
#include "breastfit/template/iso_surface.h"
#include "breastfit/template/isotropic_remesher.h"
#include "breastfit/template/plane_clip.h"

namespace breastfit::templ {

TemplateMesh build_template_mesh(const BodyField& field, const TemplateMeshOptions& o) {
  if (!(o.target_edge_mm >= 4.0 && o.target_edge_mm <= 60.0))
    throw InvalidInput("template mesh: target_edge_mm must be in [4, 60]");
  if (!(o.grid_step_mm >= 2.0 && o.grid_step_mm <= 0.75 * o.target_edge_mm + 1e-9))
    throw InvalidInput("template mesh: grid_step_mm must be in [2, 0.75 * target_edge_mm]");
  const double h = o.grid_step_mm;
  const BodyParams& P = field.params();
  // Box around the left half (x >= 0) with margin.
  const Vec3 lo(-3 * h, -190.0, P.waist_cut_z - 3 * h);
  const Vec3 hi(340.0, 200.0, P.neck_cut_z + 60.0);
  const TriangleMesh iso =
      marching_tetrahedra([&](const Vec3& p) { return field.value(p); }, lo, hi, h);

  CutPlane sym;
  sym.point = Vec3::Zero();
  sym.normal = -Vec3::UnitX();
  const std::vector<CutPlane> half_cuts = {sym, field.waist_cut(), field.neck_cut(), field.arm_cut(1)};
  const ClippedMesh clipped = clip_by_planes(iso, half_cuts);
  RemeshOptions ro;
  ro.target_edge_mm = o.target_edge_mm;
  ro.iterations = o.remesh_iterations;
  const ClippedMesh half = isotropic_remesh(clipped, field, half_cuts, ro);

  // Mirror: seam vertices (on the sym plane) are shared.
  const Index nh = half.mesh.num_vertices();
  std::vector<Index> mirror_of(nh, -1);
  Index nv = nh;
  for (Index v = 0; v < nh; ++v) mirror_of[v] = (half.on_cut[v] & 1u) ? v : nv++;
  TemplateMesh out;
  out.mesh.V.resize(nv, 3);
  out.on_cut.assign(nv, 0);
  out.mirror.assign(nv, -1);
  auto remap_bits = [](std::uint32_t m, bool right) {
    std::uint32_t r = 0;
    if (m & 2u) r |= 1u << kCutWaist;
    if (m & 4u) r |= 1u << kCutNeck;
    if (m & 8u) r |= 1u << (right ? kCutArmR : kCutArmL);
    return r;
  };
  for (Index v = 0; v < nh; ++v) {
    Vec3 p = half.mesh.V.row(v).transpose();
    if (half.on_cut[v] & 1u) p.x() = 0.0;
    out.mesh.V.row(v) = p.transpose();
    out.on_cut[v] = remap_bits(half.on_cut[v], false);
    const Index m = mirror_of[v];
    out.mirror[v] = m;
    out.mirror[m] = v;
    if (m != v) {
      out.mesh.V.row(m) = Vec3(-p.x(), p.y(), p.z()).transpose();
      out.on_cut[m] = remap_bits(half.on_cut[v], true);
    }
  }
  const Index nf = half.mesh.num_faces();
  out.mesh.F.resize(2 * nf, 3);
  for (Index f = 0; f < nf; ++f) {
    const Index a = half.mesh.F(f, 0), b = half.mesh.F(f, 1), c = half.mesh.F(f, 2);
    out.mesh.F.row(f) << a, b, c;
    out.mesh.F.row(nf + f) << mirror_of[a], mirror_of[c], mirror_of[b];
  }
  out.cuts = field.cut_planes();
  return out;
}

}  // namespace breastfit::templ
