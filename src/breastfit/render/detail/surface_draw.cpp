#include "breastfit/render/detail/surface_draw.h"

#include <algorithm>
#include <cmath>

#include "breastfit/mesh/normals.h"

namespace breastfit::render::detail {

SurfaceDraw::SurfaceDraw(const Camera& camera, const Points& V, const Triangles& F, const Points& N, const Colors& C,
                         const SurfaceStyle& style, int w, int h)
    : camera(camera),
      V(V),
      F(F),
      C(C),
      style(style),
      perspective(camera.projection == Projection::Perspective),
      forward(camera.forward()),
      light(make_lighting(camera)),
      uniform_colour(to_vec(style.colour)),
      P(camera.project_all(V, w, h)),
      computed_normals_((style.smooth && N.rows() == 0) ? mesh::vertex_normals(V, F) : Points()),
      vn(N.rows() ? N : computed_normals_) {
  order_triangles(w, h);
}

void SurfaceDraw::order_triangles(int w, int h) {
  const size_t n_faces = static_cast<size_t>(F.rows());
  area.assign(n_faces, 0.0);
  front.assign(n_faces, 0);
  const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;
  tiles = tiles_x * tiles_y;
  // Counting sort by bucket: the counts first (bucket_end[b + 1]), then their prefix sums (each
  // bucket's start), which placing the triangles advances to each bucket's end.
  std::vector<std::int32_t> bucket_of(n_faces, -1);  // -1: nothing to draw
  bucket_end.assign(2 * static_cast<size_t>(tiles) + 1, 0);
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const Projected &p0 = P[F(t, 0)], &p1 = P[F(t, 1)], &p2 = P[F(t, 2)];
    if (perspective && (p0.depth <= camera.near || p1.depth <= camera.near || p2.depth <= camera.near)) continue;
    if (!(std::isfinite(p0.depth) && std::isfinite(p1.depth) && std::isfinite(p2.depth))) continue;
    // The image is y-down, so a triangle whose corners run counter-clockwise seen from the
    // camera (its normal towards the camera) has a negative signed area in the image.
    const double a = edge(p0, p1, p2.x, p2.y);
    if (!(std::abs(a) > 1e-12)) continue;
    const bool faces_camera = a < 0;
    area[static_cast<size_t>(t)] = a;
    front[static_cast<size_t>(t)] = faces_camera;
    all_fixed = all_fixed && fixed_range(p0) && fixed_range(p1) && fixed_range(p2);
    const double cx = (p0.x + p1.x + p2.x) / 3.0, cy = (p0.y + p1.y + p2.y) / 3.0;
    const int tx = std::clamp(pixel_index(cx), 0, w - 1) / kTile, ty = std::clamp(pixel_index(cy), 0, h - 1) / kTile;
    const int bucket = (faces_camera ? 0 : tiles) + ty * tiles_x + tx;
    bucket_of[static_cast<size_t>(t)] = bucket;
    ++bucket_end[static_cast<size_t>(bucket) + 1];
  }
  for (size_t k = 1; k < bucket_end.size(); ++k) bucket_end[k] += bucket_end[k - 1];
  n_front = static_cast<size_t>(bucket_end[static_cast<size_t>(tiles)]);
  order.resize(static_cast<size_t>(bucket_end.back()));
  for (Eigen::Index t = 0; t < F.rows(); ++t)
    if (bucket_of[static_cast<size_t>(t)] >= 0)
      order[static_cast<size_t>(bucket_end[static_cast<size_t>(bucket_of[t])]++)] = static_cast<std::int32_t>(t);
}

}  // namespace breastfit::render::detail
