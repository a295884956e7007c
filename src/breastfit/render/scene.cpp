#include "breastfit/render/scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/render/colorbar.h"
#include "breastfit/render/font.h"

namespace breastfit::render {

namespace {

struct Rect {
  int x0, y0, x1, y1;  // [x0, x1) × [y0, y1)
  bool intersects(const Rect& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  bool inside(int w, int h) const { return x0 >= 0 && y0 >= 0 && x1 <= w && y1 <= h; }
};

int text_scale_of(const RenderOptions& o) {
  return o.text_scale > 0 ? o.text_scale : std::max(1, std::min(o.width, o.height) / 512);
}

/// The scalar range of a field: the options, else min/max of the finite values.
std::pair<double, double> scalar_range(const ScalarField& f) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (Eigen::Index i = 0; i < f.values.size(); ++i)
    if (std::isfinite(f.values[i])) {
      lo = std::min(lo, f.values[i]);
      hi = std::max(hi, f.values[i]);
    }
  if (!std::isfinite(lo)) lo = 0, hi = 1;
  if (f.lo) lo = *f.lo;
  if (f.hi) hi = *f.hi;
  if (!(hi > lo)) hi = lo + (std::abs(lo) > 0 ? 0.01 * std::abs(lo) : 1.0);
  return {lo, hi};
}

const ScalarField* colorbar_field(const Scene& scene, const RenderOptions& o) {
  if (!o.show_colorbar) return nullptr;
  for (const auto& m : scene.meshes)
    if (m.scalars) return &*m.scalars;
  return nullptr;
}

ColorbarSpec colorbar_spec(const ScalarField& f) {
  const auto [lo, hi] = scalar_range(f);
  ColorbarSpec spec;
  spec.map = f.map;
  spec.lo = lo;
  spec.hi = hi;
  spec.units = f.units;
  spec.label = f.label;
  return spec;
}

struct ColorbarPlacement {
  int bar_width = 0;
  int bar_height = 0;
  int reserve = 0;  // pixels kept free at the right edge
  ColorbarLayout layout;
};

ColorbarPlacement colorbar_placement(const ColorbarSpec& spec, const RenderOptions& o) {
  const int s = text_scale_of(o);
  ColorbarPlacement p;
  p.bar_width = std::max(8, o.width / 40);
  p.bar_height = std::max(20, static_cast<int>(0.32 * o.height));
  p.layout = colorbar_layout(spec, p.bar_width, p.bar_height, s);
  p.reserve = p.layout.width + 12 * s;
  return p;
}

int pad_of(const RenderOptions& o) { return 4 * text_scale_of(o); }

/// The title's font scale: one step above the text scale, smaller if the title would not fit.
int title_scale(const RenderOptions& o) {
  const int room = o.width - 2 * pad_of(o);
  int s = text_scale_of(o) + 1;
  while (s > 1 && text_size(o.title, s).width > room) --s;
  return s;
}

/// The title, cut with ".." when even scale 1 does not fit the image width.
std::string title_text(const RenderOptions& o) {
  const int room = o.width - 2 * pad_of(o);
  std::string t = o.title;
  const int s = title_scale(o);
  if (text_size(t, s).width <= room) return t;
  while (!t.empty() && text_size(t + "..", s).width > room) t.pop_back();
  return t + "..";
}

int title_bottom(const RenderOptions& o) {
  if (o.title.empty()) return 0;
  return pad_of(o) + text_size(title_text(o), title_scale(o)).height;
}

Points frame_samples(const Scene& scene) {
  Eigen::Index n = 0;
  for (const auto& m : scene.meshes) n += m.mesh.V.rows();
  for (const auto& l : scene.polylines) n += l.points.rows();
  n += static_cast<Eigen::Index>(scene.points.size());
  Points P(n, 3);
  Eigen::Index k = 0;
  for (const auto& m : scene.meshes) {
    P.middleRows(k, m.mesh.V.rows()) = m.mesh.V;
    k += m.mesh.V.rows();
  }
  for (const auto& l : scene.polylines) {
    P.middleRows(k, l.points.rows()) = l.points;
    k += l.points.rows();
  }
  for (const auto& p : scene.points) P.row(k++) = p.position.transpose();
  // Drop non-finite samples.
  Eigen::Index kept = 0;
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    if (P.row(i).allFinite()) P.row(kept++) = P.row(i);
  P.conservativeResize(kept, 3);
  return P;
}

Colors scalar_colours(const ScalarField& f, Eigen::Index nv, const std::string& name) {
  if (f.values.size() != nv)
    throw InvalidInput("render_scene: mesh '" + name + "' has " + std::to_string(nv) + " vertices but " +
                       std::to_string(f.values.size()) + " scalar values");
  const auto [lo, hi] = scalar_range(f);
  Colors C(nv, 3);
  for (Eigen::Index i = 0; i < nv; ++i) {
    const Rgb c = std::isfinite(f.values[i]) ? colormap(f.map, f.values[i], lo, hi) : Rgb{150, 150, 150};
    C(i, 0) = c.r;
    C(i, 1) = c.g;
    C(i, 2) = c.b;
  }
  return C;
}

double radius_in_pixels(const ScenePoint& p, const Rasterizer& raster) {
  if (p.radius_unit == SizeUnit::Pixels) return p.radius_px;
  const Projected q = raster.project(p.position);
  return p.radius_px / raster.camera().world_per_pixel(q.depth, raster.options().height);
}

void draw_labels(Image& img, const Scene& scene, const Rasterizer& raster, const RenderOptions& o,
                 std::vector<Rect>& occupied) {
  const int s = text_scale_of(o);
  const int pad = s + 1;
  std::vector<Rect> discs;
  auto on_canvas = [](const Projected& q) {
    return std::isfinite(q.x) && std::isfinite(q.y) && std::abs(q.x) < 1e6 && std::abs(q.y) < 1e6;
  };
  for (const auto& p : scene.points) {
    const Projected q = raster.project(p.position);
    if (!on_canvas(q)) continue;
    const int r = static_cast<int>(std::ceil(std::min(radius_in_pixels(p, raster), 1e5))) + 1;
    const int qx = static_cast<int>(std::floor(q.x)), qy = static_cast<int>(std::floor(q.y));
    discs.push_back({qx - r, qy - r, qx + r + 1, qy + r + 1});
  }
  for (size_t i = 0; i < scene.points.size(); ++i) {
    const ScenePoint& p = scene.points[i];
    if (p.label.empty() || !p.position.allFinite()) continue;
    const bool visible = raster.is_visible(p.position);
    if (!visible && !o.show_hidden) continue;
    const Projected q = raster.project(p.position);
    if (!on_canvas(q)) continue;
    const TextSize ts = text_size(p.label, s);
    const double gap = std::min(radius_in_pixels(p, raster), 1e5) + 2 + 2 * s;
    const double dg = 0.75 * gap;
    const int cx = static_cast<int>(std::lround(q.x)), cy = static_cast<int>(std::lround(q.y));
    auto at = [&](double dx, double dy) { return std::pair<int, int>{cx + int(std::lround(dx)), cy + int(std::lround(dy))}; };
    const std::pair<int, int> right = at(gap, -ts.height / 2.0), left = at(-gap - ts.width, -ts.height / 2.0);
    const std::pair<int, int> ur = at(dg, -dg - ts.height), dr = at(dg, dg), ul = at(-dg - ts.width, -dg - ts.height),
                              dl = at(-dg - ts.width, dg);
    std::vector<std::pair<int, int>> cand;
    const bool prefer_left = q.x < 0.5 * o.width;
    if (prefer_left)
      cand = {left, ul, dl, right, ur, dr};
    else
      cand = {right, ur, dr, left, ul, dl};
    const int step = ts.height + 2 * pad + 1;
    for (int k = 1; k <= 6; ++k)
      for (const auto& base : {cand[0], cand[3]}) {
        cand.emplace_back(base.first, base.second - k * step);
        cand.emplace_back(base.first, base.second + k * step);
      }
    std::optional<std::pair<int, int>> chosen;
    for (const auto& c : cand) {
      const Rect r{c.first - pad, c.second - pad, c.first + ts.width + pad, c.second + ts.height + pad};
      if (!r.inside(img.width(), img.height())) continue;
      bool clash = false;
      for (const Rect& o2 : occupied) clash = clash || r.intersects(o2);
      for (size_t j = 0; j < discs.size() && !clash; ++j) clash = r.intersects(discs[j]);
      if (!clash) {
        chosen = c;
        break;
      }
    }
    if (!chosen) chosen = cand[0];
    const Rgb text = visible ? Rgb{20, 20, 20} : Rgb{125, 125, 125};
    draw_label(img, chosen->first, chosen->second, p.label, text, {255, 255, 255}, visible ? 0.78 : 0.55, s, pad);
    occupied.push_back({chosen->first - pad, chosen->second - pad, chosen->first + ts.width + pad,
                        chosen->second + ts.height + pad});
  }
}

/// The view caption ("front view"), bottom right.
std::string view_caption(const RenderOptions& o) {
  return o.view_caption ? *o.view_caption : std::string(view_name(o.view)) + " view";
}

void draw_orientation(Image& img, const Camera& cam, const RenderOptions& o) {
  const int s = text_scale_of(o);
  const Eigen::Matrix3d A = o.body_to_world.topLeftCorner<3, 3>();
  const Vec3 r = cam.right();
  // Body axes with the letter at their positive and negative ends.
  const std::array<std::pair<Vec3, std::array<const char*, 2>>, 3> axes = {{
      {A.col(0), {"L", "R"}},  // +x = patient's left
      {A.col(1), {"P", "A"}},  // +y = posterior
      {A.col(2), {"S", "I"}},  // +z = superior
  }};
  for (const auto& [axis, letters] : axes) {
    if (!(axis.norm() > 0)) continue;
    const double h = axis.normalized().dot(r);
    if (std::abs(h) < 0.6) continue;
    const int ls = 2 * s;
    const TextSize ts = text_size("L", ls);
    const int y = o.height / 2 - ts.height / 2;
    const int pad = pad_of(o);
    const char* right_letter = h > 0 ? letters[0] : letters[1];
    const char* left_letter = h > 0 ? letters[1] : letters[0];
    draw_label(img, pad + 2, y, left_letter, {110, 110, 110}, {255, 255, 255}, 0.6, ls, s);
    draw_label(img, o.width - pad - 2 - ts.width, y, right_letter, {110, 110, 110}, {255, 255, 255}, 0.6, ls, s);
    break;
  }
  // View caption, bottom right.
  const std::string caption = view_caption(o);
  const TextSize cs = text_size(caption, s);
  draw_text(img, o.width - pad_of(o) - cs.width, o.height - pad_of(o) - cs.height, caption, {120, 120, 120}, s);
}

/// The legend's entries: the first polyline of each name, in scene order.
std::vector<const ScenePolyline*> legend_entries(const Scene& scene, const RenderOptions& o) {
  std::vector<const ScenePolyline*> entries;
  if (!o.show_legend) return entries;
  std::set<std::string> seen;
  for (const auto& l : scene.polylines)
    if (!l.name.empty() && seen.insert(l.name).second) entries.push_back(&l);
  return entries;
}

/// Where the legend's entries go: flowed left to right in rows across the bottom of the image,
/// the view caption at the right end of the last row (or on a row of its own when it does not
/// fit there), inside a band that the framing keeps clear of the scene.
struct LegendLayout {
  Rect box{0, 0, 0, 0};                     ///< the entries, background box included
  int band_top = 0;                          ///< top of the band kept clear (entries and caption)
  std::vector<std::pair<int, int>> origins;  ///< top-left of each entry's swatch row
  int swatch = 0;
};

LegendLayout legend_layout(const std::vector<const ScenePolyline*>& entries, const RenderOptions& o) {
  LegendLayout L;
  if (entries.empty()) return L;
  const int s = text_scale_of(o);
  const int pad = pad_of(o);
  const int line_h = kLineHeight * s + 2 * s;
  L.swatch = 14 * s;
  const int gap = 8 * s;
  const int x0 = pad + 2;
  const int right = std::max(x0 + 1, o.width - pad);
  int x = x0, row = 0, widest = x0;
  std::vector<std::pair<int, int>> cells;  // (x, row)
  for (const auto* e : entries) {
    const int w = L.swatch + 3 * s + text_size(e->name, s).width;
    if (x > x0 && x + w > right) {
      x = x0;
      ++row;
    }
    cells.emplace_back(x, row);
    widest = std::max(widest, x + w);
    x += w + gap;
  }
  // The caption shares the last row when it fits right of the last entry.
  const int caption_w = o.show_orientation ? text_size(view_caption(o), s).width + 2 * pad : 0;
  const int caption_rows = caption_w > 0 && x + caption_w > right ? 1 : 0;  // x: after the last entry and a gap
  const int rows = row + 1;
  const int box_h = rows * line_h - 2 * s;
  const int y0 = o.height - pad - box_h - caption_rows * line_h;
  for (const auto& [cx, r] : cells) L.origins.emplace_back(cx, y0 + r * line_h);
  L.box = {x0 - s - 1, y0 - s - 1, widest + s + 1, y0 + box_h + s + 1};
  L.band_top = L.box.y0;
  return L;
}

/// Pixels kept free at the bottom of the image for the legend.
int legend_reserve(const Scene& scene, const RenderOptions& o) {
  const LegendLayout L = legend_layout(legend_entries(scene, o), o);
  if (L.origins.empty()) return 0;
  return std::min(o.height - L.band_top + pad_of(o), o.height / 2);
}

void draw_legend(Image& img, const Scene& scene, const RenderOptions& o, std::vector<Rect>& occupied) {
  const std::vector<const ScenePolyline*> entries = legend_entries(scene, o);
  const LegendLayout L = legend_layout(entries, o);
  if (entries.empty()) return;
  const int s = text_scale_of(o);
  img.fill_rect(L.box.x0, L.box.y0, L.box.x1, L.box.y1, {255, 255, 255}, 0.75);
  for (size_t i = 0; i < entries.size(); ++i) {
    const auto [x, y] = L.origins[i];
    const int mid = y + (kGlyphHeight - 1) * s / 2;
    const int th = std::max(2, static_cast<int>(std::lround(entries[i]->width_px)));
    img.fill_rect(x, mid - th / 2, x + L.swatch, mid - th / 2 + th, entries[i]->colour);
    draw_text(img, x + L.swatch + 3 * s, y, entries[i]->name, {30, 30, 30}, s);
  }
  occupied.push_back(L.box);
}

}  // namespace

Eigen::AlignedBox3d Scene::bounds() const {
  Eigen::AlignedBox3d box;
  auto add = [&](const Points& P) {
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      if (P.row(i).allFinite()) box.extend(Vec3(P.row(i).transpose()));
  };
  for (const auto& m : meshes) add(m.mesh.V);
  for (const auto& l : polylines) add(l.points);
  for (const auto& p : points)
    if (p.position.allFinite()) box.extend(p.position);
  return box;
}

void RenderOptions::validate() const {
  RasterOptions ro;
  ro.width = width;
  ro.height = height;
  ro.supersample = supersample;
  ro.hidden_alpha = hidden_alpha;
  ro.depth_bias = depth_bias.value_or(0.0);
  ro.validate();
  if (!(margin >= 0 && margin < 0.45)) throw InvalidInput("RenderOptions: margin must be in [0, 0.45)");
  if (text_scale < 0 || text_scale > 16) throw InvalidInput("RenderOptions: text_scale must be in [0, 16]");
  if (projection == Projection::Perspective && !(fov_y_deg > 0 && fov_y_deg < 179))
    throw InvalidInput("RenderOptions: fov_y_deg must be in (0, 179)");
  if (!body_to_world.allFinite()) throw InvalidInput("RenderOptions: body_to_world must be finite");
}

Camera scene_camera(const Scene& scene, const RenderOptions& o) {
  if (o.camera) return *o.camera;
  Points P;
  if (o.frame) {
    if (o.frame->isEmpty()) throw InvalidInput("render_scene: the frame box is empty");
    P.resize(8, 3);
    for (int i = 0; i < 8; ++i)
      P.row(i) = o.frame->corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)).transpose();
  } else {
    P = frame_samples(scene);
  }
  if (P.rows() == 0) throw InvalidInput("render_scene: the scene is empty (nothing to frame)");
  const ViewDirections vd = view_directions(o.view, o.body_to_world);
  int reserve = 0;
  if (const ScalarField* f = colorbar_field(scene, o)) reserve = colorbar_placement(colorbar_spec(*f), o).reserve;
  reserve = std::min(reserve, o.width / 3);
  const int top_reserve = std::min(title_bottom(o), o.height / 4);
  const int bottom_reserve = legend_reserve(scene, o);
  const int free_h = o.height - top_reserve - bottom_reserve;
  const double aspect = static_cast<double>(o.width - reserve) / free_h;
  Camera cam = frame_points(P, vd.forward, vd.up, aspect, o.margin, o.projection, o.fov_y_deg);
  // frame_points filled a (width - reserve) × free_h viewport: enlarge the view to the whole
  // image and shift it so that the scene sits left of the colour bar, between the title and the
  // legend.
  const double depth = (cam.target - cam.eye).dot(cam.forward());
  if (cam.projection == Projection::Orthographic) {
    cam.view_height *= static_cast<double>(o.height) / free_h;
  } else {
    const double k = static_cast<double>(o.height) / free_h;
    const double t = std::tan(0.5 * cam.fov_y_deg * 3.14159265358979323846 / 180.0);
    cam.fov_y_deg = 2.0 * std::atan(t * k) * 180.0 / 3.14159265358979323846;
  }
  const double wpp = cam.world_per_pixel(depth, o.height);
  const Vec3 shift =
      cam.right() * (0.5 * reserve * wpp) + cam.true_up() * (0.5 * (top_reserve - bottom_reserve) * wpp);
  cam.eye += shift;
  cam.target += shift;
  return cam;
}

std::optional<Eigen::AlignedBox2i> legend_box(const Scene& scene, const RenderOptions& o) {
  const LegendLayout L = legend_layout(legend_entries(scene, o), o);
  if (L.origins.empty()) return std::nullopt;
  return Eigen::AlignedBox2i(Eigen::Vector2i(L.box.x0, L.box.y0), Eigen::Vector2i(L.box.x1, L.box.y1));
}

Rasterizer draw_scene_meshes(const Scene& scene, const RenderOptions& o) {
  o.validate();
  const Camera cam = scene_camera(scene, o);
  const Eigen::AlignedBox3d box = scene.bounds();
  RasterOptions ro;
  ro.width = o.width;
  ro.height = o.height;
  ro.supersample = o.supersample;
  ro.background = o.background;
  ro.depth_bias = o.depth_bias.value_or(box.isEmpty() ? 0.0 : 0.01 * box.diagonal().norm());
  ro.show_hidden_overlays = o.show_hidden;
  ro.hidden_alpha = o.hidden_alpha;
  Rasterizer raster(cam, ro);

  static const Points kNoNormals;
  static const Colors kNoColours;
  for (const SceneMesh& m : scene.meshes) {
    const Points& N = m.mesh.has_normals() ? m.mesh.N : kNoNormals;
    if (m.scalars) {
      // Colour-map fidelity: no highlight, softer shading, so colours match the colour bar.
      SurfaceStyle style = m.style;
      style.specular = 0.0;
      style.ambient = std::max(style.ambient, 0.5);
      const double diffuse = style.headlight + style.key_light;
      if (diffuse > 0) {
        style.headlight *= (1.0 - style.ambient) / diffuse;
        style.key_light *= (1.0 - style.ambient) / diffuse;
      }
      raster.draw_mesh(m.mesh.V, m.mesh.F, N, scalar_colours(*m.scalars, m.mesh.V.rows(), m.name), style);
    } else {
      const Colors& C = (m.use_vertex_colours && m.mesh.has_colors()) ? m.mesh.C : kNoColours;
      raster.draw_mesh(m.mesh.V, m.mesh.F, N, C, m.style);
    }
  }
  return raster;
}

Image finish_scene(Rasterizer raster, const Scene& scene, const RenderOptions& o) {
  o.validate();
  const Camera& cam = raster.camera();
  for (const SceneMesh& m : scene.meshes)
    if (m.wireframe) raster.draw_wireframe(m.mesh.V, m.mesh.F, m.wireframe_style);
  for (const ScenePolyline& l : scene.polylines) {
    LineStyle ls;
    ls.colour = l.colour;
    ls.width_px = l.width_px;
    raster.draw_polyline(l.points, l.closed, ls);
  }
  for (const ScenePoint& p : scene.points) {
    if (!p.position.allFinite()) continue;
    PointStyle ps;
    ps.colour = p.colour;
    ps.radius = p.radius_px;
    ps.unit = p.radius_unit;
    raster.draw_point(p.position, ps);
  }

  Image img = raster.resolve();
  const int s = text_scale_of(o);
  std::vector<Rect> occupied;
  const int pad = pad_of(o);
  if (!o.title.empty()) {
    const TextSize ts = text_size(title_text(o), title_scale(o));
    occupied.push_back({0, 0, pad + ts.width + pad, pad + ts.height + pad});
  }
  if (const ScalarField* f = colorbar_field(scene, o)) {
    const ColorbarSpec spec = colorbar_spec(*f);
    const ColorbarPlacement cp = colorbar_placement(spec, o);
    const int x = o.width - cp.layout.width - 2 * pad;
    const int y = std::max(title_bottom(o), 0) + 3 * pad;
    draw_colorbar(img, x, y, cp.bar_width, cp.bar_height, spec, s);
    occupied.push_back({x - pad, y - pad, x + cp.layout.width + pad, y + cp.layout.height + pad});
  }
  if (o.show_legend) draw_legend(img, scene, o, occupied);
  if (o.show_labels) draw_labels(img, scene, raster, o, occupied);
  if (o.show_orientation) draw_orientation(img, cam, o);
  if (!o.title.empty()) draw_text(img, pad, pad, title_text(o), {20, 20, 20}, title_scale(o));
  return img;
}

Image render_scene(const Scene& scene, const RenderOptions& o) { return finish_scene(draw_scene_meshes(scene, o), scene, o); }

}  // namespace breastfit::render
