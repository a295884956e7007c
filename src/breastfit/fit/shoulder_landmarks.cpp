#include "breastfit/fit/shoulder_landmarks.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace breastfit::fit {

std::optional<SternumFrame> sternum_frame(const Vec3& notch, const Vec3& xiphoid, const Vec3& nipple_R,
                                          const Vec3& nipple_L, char side) {
  SternumFrame f;
  f.notch = notch;
  f.length_mm = (notch - xiphoid).norm();
  if (!(f.length_mm > 0)) return std::nullopt;
  f.up = (notch - xiphoid) / f.length_mm;
  const Vec3 across = f.up.cross(nipple_L - nipple_R);
  if (!(across.norm() > 0)) return std::nullopt;
  f.front = across.normalized();
  if ((0.5 * (nipple_L + nipple_R) - xiphoid).dot(f.front) < 0) f.front = -f.front;
  f.lateral = f.up.cross(f.front);
  if (f.lateral.dot(nipple_L - nipple_R) < 0) f.lateral = -f.lateral;  // towards the left
  if (side == 'R') f.lateral = -f.lateral;
  if (!f.front.allFinite() || !f.lateral.allFinite()) return std::nullopt;
  return f;
}

SternumCoordinates sternum_coordinates(const SternumFrame& f, const Vec3& p) {
  const Vec3 d = p - f.notch;
  return {d.dot(f.up), d.dot(f.front), d.dot(f.lateral)};
}

namespace {

using Local = SternumCoordinates;

// The scan vertex with the highest `score` among those `in` the strip; nullopt when there is none
// (or without a sternum).
template <class InStrip, class Score>
std::optional<Vec3> best_in_strip(const Points& V, const SternumFrame& frame, InStrip in, Score score) {
  if (!(frame.length_mm > 0)) return std::nullopt;
  Index best = -1;
  double top = -std::numeric_limits<double>::infinity();
  for (Index i = 0; i < V.rows(); ++i) {
    const Local p = sternum_coordinates(frame, V.row(i).transpose());
    if (!in(p)) continue;
    const double s = score(p);
    if (s > top) {
      top = s;
      best = i;
    }
  }
  if (best < 0) return std::nullopt;
  return V.row(best).transpose();
}

// `p` unless it lies farther than max_shift_mm from the fitted point.
std::optional<Vec3> near_fitted(const std::optional<Vec3>& p, const Vec3& fitted, const ShoulderLandmarkOptions& o) {
  if (!p || (*p - fitted).norm() > o.max_shift_mm) return std::nullopt;
  return p;
}

}  // namespace

bool arms_abducted_on_scan(const Points& scan_vertices, const SternumFrame& frame,
                           const ShoulderLandmarkOptions& o) {
  if (!(frame.length_mm > 0)) return false;
  double out = -std::numeric_limits<double>::infinity(), in = out;  // the frame's side, the other
  for (Index i = 0; i < scan_vertices.rows(); ++i) {
    const Local p = sternum_coordinates(frame, scan_vertices.row(i).transpose());
    if (p.height > 0 || p.height < -o.reach_band * frame.length_mm) continue;
    out = std::max(out, p.lateral);
    in = std::max(in, -p.lateral);
  }
  return std::min(out, in) >= o.abducted_reach * frame.length_mm;
}

std::optional<Vec3> midaxillary_on_scan(const Points& scan_vertices, const Vec3& fitted, const SternumFrame& frame,
                                        const ShoulderLandmarkOptions& o) {
  const Local f = sternum_coordinates(frame, fitted);
  const double height = -o.midaxillary_drop * frame.length_mm, w = o.strip_half_width_mm;
  const auto p = best_in_strip(
      scan_vertices, frame,
      [&](const Local& p) { return std::abs(p.height - height) <= w && std::abs(p.front - f.front) <= w; },
      [&](const Local& p) { return -std::abs(p.lateral - f.lateral); });
  return near_fitted(p, fitted, o);
}

std::optional<Vec3> acromion_on_scan(const Points& scan_vertices, const Vec3& fitted, const SternumFrame& frame,
                                     const ShoulderLandmarkOptions& o) {
  const Local f = sternum_coordinates(frame, fitted);
  const double breadth = o.acromion_breadth * frame.length_mm, w = o.strip_half_width_mm;
  const auto p = best_in_strip(
      scan_vertices, frame,
      [&](const Local& p) {
        return std::abs(p.lateral - breadth) <= w && std::abs(p.front - f.front) <= w &&
               std::abs(p.height - f.height) <= o.acromion_height_window_mm;
      },
      [](const Local& p) { return p.height; });
  return near_fitted(p, fitted, o);
}

std::optional<Vec3> abducted_pectoral_insertion_on_scan(const Points& scan_vertices, const SternumFrame& frame,
                                                        const ShoulderLandmarkOptions& o) {
  const double breadth = o.pectoral_breadth * frame.length_mm, height = -o.pectoral_drop * frame.length_mm;
  const double w = o.strip_half_width_mm;
  return best_in_strip(
      scan_vertices, frame,
      [&](const Local& p) { return std::abs(p.lateral - breadth) <= w && std::abs(p.height - height) <= w; },
      [](const Local& p) { return p.front; });
}

std::optional<Vec3> hanging_pectoral_insertion_on_scan(const Points& scan_vertices, const Vec3& arm_front,
                                                       const SternumFrame& frame,
                                                       const ShoulderLandmarkOptions& o) {
  const Local a = sternum_coordinates(frame, arm_front);
  const double height = -o.hanging_pectoral_drop * frame.length_mm, w = o.strip_half_width_mm;
  return best_in_strip(
      scan_vertices, frame,
      [&](const Local& p) {
        return std::abs(p.height - height) <= w && std::abs(p.lateral - a.lateral) <= w &&
               p.front > a.front - o.max_behind_mm;
      },
      [](const Local& p) { return p.front; });
}

}  // namespace breastfit::fit
