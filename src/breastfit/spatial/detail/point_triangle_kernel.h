#pragma once
/// \file Inline point–triangle kernel shared by point_triangle.cpp and the closest-point index
/// (private to the spatial layer). See spatial/point_triangle.h for the contract.
#include <cmath>

#include "breastfit/spatial/closest_point_index.h"

namespace breastfit::spatial::detail {

/// sin² of the angle at `a` below which a triangle is treated as degenerate (edges only).
inline constexpr double kDegenerateSinSq = 1e-12;

/// True when triangle (a, b, c) has (nearly) zero area relative to its edge lengths at a.
inline bool is_degenerate_triangle(const double* a, const double* b, const double* c) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double nx = ab[1] * ac[2] - ab[2] * ac[1];
  const double ny = ab[2] * ac[0] - ab[0] * ac[2];
  const double nz = ab[0] * ac[1] - ab[1] * ac[0];
  const double n2 = nx * nx + ny * ny + nz * nz;
  const double ab2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
  const double ac2 = ac[0] * ac[0] + ac[1] * ac[1] + ac[2] * ac[2];
  return !(n2 > kDegenerateSinSq * ab2 * ac2);
}

/// Closest point on segment x→y; t in [0, 1] (0 for a zero-length segment). Returns sq dist.
inline double closest_on_segment(const double* p, const double* x, const double* y, double& t) {
  const double d[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
  const double xp[3] = {p[0] - x[0], p[1] - x[1], p[2] - x[2]};
  const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double num = d[0] * xp[0] + d[1] * xp[1] + d[2] * xp[2];
  if (num <= 0.0 || !(dd > 0.0)) {
    t = 0.0;
  } else if (num >= dd) {
    t = 1.0;
  } else {
    t = num / dd;
  }
  const double r[3] = {xp[0] - t * d[0], xp[1] - t * d[1], xp[2] - t * d[2]};
  return r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
}

/// Closest of the three edges of a (degenerate) triangle; ties go to the first edge in the
/// order a–b, b–c, c–a.
inline double closest_on_edges(const double* p, const double* a, const double* b,
                               const double* c, double* bary, ClosestFeature& feature) {
  double t01 = 0.0, t12 = 0.0, t20 = 0.0;
  const double s01 = closest_on_segment(p, a, b, t01);
  const double s12 = closest_on_segment(p, b, c, t12);
  const double s20 = closest_on_segment(p, c, a, t20);
  int best = 0;
  double s = s01;
  if (s12 < s) { best = 1; s = s12; }
  if (s20 < s) { best = 2; s = s20; }
  if (best == 0) {
    bary[0] = 1.0 - t01; bary[1] = t01; bary[2] = 0.0;
    feature = t01 == 0.0 ? ClosestFeature::Vertex0
              : t01 == 1.0 ? ClosestFeature::Vertex1 : ClosestFeature::Edge01;
  } else if (best == 1) {
    bary[0] = 0.0; bary[1] = 1.0 - t12; bary[2] = t12;
    feature = t12 == 0.0 ? ClosestFeature::Vertex1
              : t12 == 1.0 ? ClosestFeature::Vertex2 : ClosestFeature::Edge12;
  } else {
    bary[0] = t20; bary[1] = 0.0; bary[2] = 1.0 - t20;
    feature = t20 == 0.0 ? ClosestFeature::Vertex2
              : t20 == 1.0 ? ClosestFeature::Vertex0 : ClosestFeature::Edge20;
  }
  if (feature == ClosestFeature::Vertex0) { bary[0] = 1.0; bary[1] = 0.0; bary[2] = 0.0; }
  if (feature == ClosestFeature::Vertex1) { bary[0] = 0.0; bary[1] = 1.0; bary[2] = 0.0; }
  if (feature == ClosestFeature::Vertex2) { bary[0] = 0.0; bary[1] = 0.0; bary[2] = 1.0; }
  return s;
}

inline double sq_dist_to_combination(const double* p, const double* a, const double* b,
                                     const double* c, const double* bary) {
  double s = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double x = bary[0] * a[k] + bary[1] * b[k] + bary[2] * c[k];
    const double r = p[k] - x;
    s += r * r;
  }
  return s;
}

/// Ericson's region method. `degenerate` must equal is_degenerate_triangle(a, b, c) (callers
/// that test a triangle many times precompute it). Returns the squared distance.
inline double closest_point_on_triangle_kernel(const double* p, const double* a, const double* b,
                                               const double* c, bool degenerate, double* bary,
                                               ClosestFeature& feature) {
  if (degenerate) return closest_on_edges(p, a, b, c, bary, feature);
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  const double d1 = ab[0] * ap[0] + ab[1] * ap[1] + ab[2] * ap[2];
  const double d2 = ac[0] * ap[0] + ac[1] * ap[1] + ac[2] * ap[2];
  if (d1 <= 0.0 && d2 <= 0.0) {
    bary[0] = 1.0; bary[1] = 0.0; bary[2] = 0.0;
    feature = ClosestFeature::Vertex0;
    return ap[0] * ap[0] + ap[1] * ap[1] + ap[2] * ap[2];
  }
  const double bp[3] = {p[0] - b[0], p[1] - b[1], p[2] - b[2]};
  const double d3 = ab[0] * bp[0] + ab[1] * bp[1] + ab[2] * bp[2];
  const double d4 = ac[0] * bp[0] + ac[1] * bp[1] + ac[2] * bp[2];
  if (d3 >= 0.0 && d4 <= d3) {
    bary[0] = 0.0; bary[1] = 1.0; bary[2] = 0.0;
    feature = ClosestFeature::Vertex1;
    return bp[0] * bp[0] + bp[1] * bp[1] + bp[2] * bp[2];
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double den = d1 - d3;  // = |ab|² without cancellation (d1 >= 0 >= d3)
    const double v = den > 0.0 ? d1 / den : 0.0;
    bary[0] = 1.0 - v; bary[1] = v; bary[2] = 0.0;
    feature = ClosestFeature::Edge01;
    const double r[3] = {ap[0] - v * ab[0], ap[1] - v * ab[1], ap[2] - v * ab[2]};
    return r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  }
  const double cp[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  const double d5 = ab[0] * cp[0] + ab[1] * cp[1] + ab[2] * cp[2];
  const double d6 = ac[0] * cp[0] + ac[1] * cp[1] + ac[2] * cp[2];
  if (d6 >= 0.0 && d5 <= d6) {
    bary[0] = 0.0; bary[1] = 0.0; bary[2] = 1.0;
    feature = ClosestFeature::Vertex2;
    return cp[0] * cp[0] + cp[1] * cp[1] + cp[2] * cp[2];
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double den = d2 - d6;
    const double w = den > 0.0 ? d2 / den : 0.0;
    bary[0] = 1.0 - w; bary[1] = 0.0; bary[2] = w;
    feature = ClosestFeature::Edge20;
    const double r[3] = {ap[0] - w * ac[0], ap[1] - w * ac[1], ap[2] - w * ac[2]};
    return r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  }
  const double va = d3 * d6 - d5 * d4;
  const double e43 = d4 - d3, e56 = d5 - d6;
  if (va <= 0.0 && e43 >= 0.0 && e56 >= 0.0) {
    const double den = e43 + e56;
    const double w = den > 0.0 ? e43 / den : 0.0;
    bary[0] = 0.0; bary[1] = 1.0 - w; bary[2] = w;
    feature = ClosestFeature::Edge12;
    const double bc[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    const double r[3] = {bp[0] - w * bc[0], bp[1] - w * bc[1], bp[2] - w * bc[2]};
    return r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  }
  const double den = va + vb + vc;
  if (!(den > 0.0)) return closest_on_edges(p, a, b, c, bary, feature);
  const double inv = 1.0 / den;
  const double v = vb * inv, w = vc * inv;
  bary[0] = 1.0 - v - w; bary[1] = v; bary[2] = w;
  feature = ClosestFeature::Face;
  const double r[3] = {ap[0] - v * ab[0] - w * ac[0], ap[1] - v * ab[1] - w * ac[1],
                       ap[2] - v * ab[2] - w * ac[2]};
  return r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
}

}  // namespace breastfit::spatial::detail
