#pragma once
// Distance between two convex bodies given by their support mappings (Gilbert-Johnson-Keerthi): the
// closest point of the Minkowski difference A - B to the origin, found on a simplex of at most four support
// points that is refined until the support in the direction of the closest point brings no progress.
#include <algorithm>
#include <array>
#include <cmath>

#include "steady/vec.hpp"

namespace steady::detail {

// Closest point to the origin of the simplex `pts[0..n)`; keeps in `pts` only the vertices of the smallest
// face that contains it. Returns the closest point; n becomes 0 when the origin is inside a tetrahedron.
inline Vec3 closest_on_simplex(std::array<Vec3, 4>& pts, int& n) {
  if (n == 1) return pts[0];
  if (n == 2) {
    const Vec3 a = pts[0], b = pts[1], ab = b - a;
    const double t = -glm::dot(a, ab) / std::max(glm::dot(ab, ab), 1e-300);
    if (t <= 0.0) {
      n = 1;
      return a;
    }
    if (t >= 1.0) {
      pts[0] = b;
      n = 1;
      return b;
    }
    return a + t * ab;
  }
  if (n == 3) {
    // Regions of the triangle (a, b, c) by barycentric signs.
    const Vec3 a = pts[0], b = pts[1], c = pts[2];
    const Vec3 ab = b - a, ac = c - a, ap = -a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) {
      n = 1;
      return a;
    }
    const Vec3 bp = -b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) {
      pts[0] = b;
      n = 1;
      return b;
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
      const double v = d1 / (d1 - d3);
      n = 2;
      return a + v * ab;
    }
    const Vec3 cp = -c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) {
      pts[0] = c;
      n = 1;
      return c;
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
      const double w = d2 / (d2 - d6);
      pts[1] = c;
      n = 2;
      return a + w * ac;
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
      const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      pts[0] = b;
      pts[1] = c;
      n = 2;
      return b + w * (c - b);
    }
    const double sum = va + vb + vc;
    if (!(std::abs(sum) > 1e-30 * (glm::dot(ab, ab) * glm::dot(ac, ac) + 1e-300))) {
      // A degenerate (collinear) triangle: the closest of its edges.
      std::array<Vec3, 4> e1{a, b}, e2{a, c}, e3{b, c};
      int n1 = 2, n2 = 2, n3 = 2;
      const Vec3 q1 = closest_on_simplex(e1, n1), q2 = closest_on_simplex(e2, n2), q3 = closest_on_simplex(e3, n3);
      const double d1s = glm::dot(q1, q1), d2s = glm::dot(q2, q2), d3s = glm::dot(q3, q3);
      if (d1s <= d2s && d1s <= d3s) {
        pts = e1;
        n = n1;
        return q1;
      }
      if (d2s <= d3s) {
        pts = e2;
        n = n2;
        return q2;
      }
      pts = e3;
      n = n3;
      return q3;
    }
    const double denom = 1.0 / sum;
    return a + ab * (vb * denom) + ac * (vc * denom);
  }
  // Tetrahedron: the origin is inside unless it lies beyond a face; then the closest point is on the
  // closest such face. A flat tetrahedron (its fourth point adds no volume) has no inside: the closest point
  // is on the closest of its faces.
  const int faces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  const double edge = std::max({glm::length(pts[1] - pts[0]), glm::length(pts[2] - pts[0]), glm::length(pts[3] - pts[0])});
  const double volume6 = std::abs(glm::dot(pts[1] - pts[0], glm::cross(pts[2] - pts[0], pts[3] - pts[0])));
  const bool flat = !(volume6 > 1e-12 * edge * edge * edge);
  double best = -1.0;
  Vec3 best_point(0.0);
  std::array<Vec3, 4> best_pts{};
  int best_n = 0;
  bool outside = false;
  for (const auto& f : faces) {
    const Vec3 a = pts[f[0]], b = pts[f[1]], c = pts[f[2]], d = pts[f[3]];
    const Vec3 normal = glm::cross(b - a, c - a);
    const double side_origin = glm::dot(-a, normal), side_other = glm::dot(d - a, normal);
    if (!flat && side_origin * side_other >= 0.0) continue;  // origin on the same side as the fourth vertex
    outside = true;
    std::array<Vec3, 4> tri{a, b, c, Vec3(0.0)};
    int m = 3;
    const Vec3 q = closest_on_simplex(tri, m);
    const double dist = glm::dot(q, q);
    if (best < 0.0 || dist < best) {
      best = dist;
      best_point = q;
      best_pts = tri;
      best_n = m;
    }
  }
  if (!outside) {
    n = 0;
    return Vec3(0.0);
  }
  pts = best_pts;
  n = best_n;
  return best_point;
}

// Distance between convex A and B (0 when they intersect). support_a(d) and support_b(d) return a point of
// the body farthest along d. `tolerance` is absolute (the length scale of the bodies times a small factor).
template <class SupportA, class SupportB>
double convex_distance(const SupportA& support_a, const SupportB& support_b, const Vec3& inner_a, const Vec3& inner_b,
                       double tolerance) {
  std::array<Vec3, 4> pts;
  int n = 0;
  Vec3 v = inner_a - inner_b;
  if (glm::dot(v, v) == 0.0) v = Vec3(1.0, 0.0, 0.0);
  for (int iteration = 0; iteration < 96; ++iteration) {
    const Vec3 w = support_a(-v) - support_b(v);
    const double vv = glm::dot(v, v);
    // No support point is closer to the origin than v by more than the tolerance: v is the distance.
    if (vv - glm::dot(v, w) <= tolerance * std::sqrt(vv)) return std::sqrt(vv);
    pts[n++] = w;
    v = closest_on_simplex(pts, n);
    if (n == 0 || glm::dot(v, v) <= tolerance * tolerance) return 0.0;
  }
  return std::sqrt(glm::dot(v, v));
}

}  // namespace steady::detail
