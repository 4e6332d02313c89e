#include "steady/lattice/convex_distance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace steady {

namespace {

// The point of a simplex (1 to 4 vertices) closest to the origin, and the smallest face of the simplex that holds
// it (the vertices kept for the next GJK step).
struct Simplex {
  std::array<Vec3, 4> p;
  int size = 0;
};

Vec3 closest_on_segment(Simplex& s) {
  const Vec3 a = s.p[0], b = s.p[1];
  const Vec3 ab = b - a;
  const double t = -glm::dot(a, ab);
  if (t <= 0.0) {
    s.size = 1;
    return a;
  }
  const double len2 = glm::dot(ab, ab);
  if (t >= len2) {
    s.p[0] = b;
    s.size = 1;
    return b;
  }
  return a + (t / len2) * ab;
}

// Closest point of triangle abc to the origin by Voronoi regions of its vertices, edges and face.
Vec3 closest_on_triangle(Simplex& s) {
  const Vec3 a = s.p[0], b = s.p[1], c = s.p[2];
  const Vec3 ab = b - a, ac = c - a, ap = -a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    s.size = 1;
    return a;
  }
  const Vec3 bp = -b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) {
    s.p[0] = b;
    s.size = 1;
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    s.size = 2;  // a, b
    return a + (d1 / (d1 - d3)) * ab;
  }
  const Vec3 cp = -c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) {
    s.p[0] = c;
    s.size = 1;
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    s.p[1] = c;
    s.size = 2;  // a, c
    return a + (d2 / (d2 - d6)) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    s.p[0] = b;
    s.p[1] = c;
    s.size = 2;  // b, c
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {  // collinear vertices: the closest point lies on one of the edges
    Simplex best;
    double best_d2 = std::numeric_limits<double>::infinity();
    Vec3 best_q(0.0);
    for (const auto& e : {std::array<Vec3, 2>{a, b}, std::array<Vec3, 2>{a, c}, std::array<Vec3, 2>{b, c}}) {
      Simplex t;
      t.p = {e[0], e[1], Vec3(0.0), Vec3(0.0)};
      t.size = 2;
      const Vec3 q = closest_on_segment(t);
      if (glm::dot(q, q) < best_d2) {
        best_d2 = glm::dot(q, q);
        best_q = q;
        best = t;
      }
    }
    s = best;
    return best_q;
  }
  // Inside the face: the projection of the origin on the triangle's plane (more accurate than the barycentric
  // combination when the triangle is long and thin).
  const Vec3 n = glm::cross(ab, ac);
  return n * (glm::dot(n, a) / glm::dot(n, n));
}

// Closest point of a tetrahedron: the origin is inside, or the closest point lies on a face it is outside of.
Vec3 closest_on_tetrahedron(Simplex& s, bool& inside) {
  static const int faces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  const double volume = glm::dot(s.p[1] - s.p[0], glm::cross(s.p[2] - s.p[0], s.p[3] - s.p[0]));
  const double size = std::max({glm::length(s.p[1] - s.p[0]), glm::length(s.p[2] - s.p[0]),
                                glm::length(s.p[3] - s.p[0])});
  const bool flat = !(std::abs(volume) > 1e-13 * size * size * size);
  inside = !flat;
  double best = std::numeric_limits<double>::infinity();
  Vec3 best_point(0.0);
  Simplex best_simplex;
  for (const auto& f : faces) {
    const Vec3 a = s.p[f[0]], b = s.p[f[1]], c = s.p[f[2]], d = s.p[f[3]];
    const Vec3 n = glm::cross(b - a, c - a);
    const double side_origin = glm::dot(-a, n), side_d = glm::dot(d - a, n);
    if (!flat) {
      if (side_origin * side_d >= 0.0) continue;  // the origin is on the inner side of this face
      inside = false;
    }
    Simplex t;
    t.p = {a, b, c, Vec3(0.0)};
    t.size = 3;
    const Vec3 q = closest_on_triangle(t);
    const double d2 = glm::dot(q, q);
    if (d2 < best) {
      best = d2;
      best_point = q;
      best_simplex = t;
    }
  }
  if (!inside) s = best_simplex;
  return best_point;
}

}  // namespace

Vec3 disk_support(const Circle& disk, const Vec3& direction) {
  const Vec3 q = direction - glm::dot(direction, disk.normal) * disk.normal;
  const double len = glm::length(q);
  if (!(len > 1e-300)) return disk.center;
  return disk.center + (disk.radius / len) * q;
}

Vec3 disk_hull_support(const Circle& a, const Circle& b, const Vec3& direction) {
  const Vec3 pa = disk_support(a, direction), pb = disk_support(b, direction);
  return glm::dot(direction, pa) >= glm::dot(direction, pb) ? pa : pb;
}

DistanceBounds convex_distance(const SupportMap& a, const SupportMap& b, double stop_above, double stop_below,
                               double relative_tolerance, int max_iterations) {
  DistanceBounds out;
  Simplex s;
  Vec3 d(1.0, 0.0, 0.0);
  s.p[0] = a(d) - b(-d);
  s.size = 1;
  Vec3 v = s.p[0];
  double lower = 0.0;
  for (int it = 0; it < max_iterations; ++it) {
    const double vlen = glm::length(v);
    out.upper = vlen;
    out.lower = lower;
    if (vlen <= stop_below || vlen == 0.0) return out;
    const Vec3 w = a(-v) - b(v);
    // Rounding in the closest point of a sliver simplex can push the bound past |v| by ~1e-8 relative.
    lower = std::min(vlen, std::max(lower, glm::dot(v, w) / vlen));
    out.lower = lower;
    if (lower > stop_above) return out;
    if (vlen - lower <= relative_tolerance * vlen) return out;
    // No progress: w is already a vertex of the simplex.
    for (int i = 0; i < s.size; ++i)
      if (s.p[i] == w) return out;
    s.p[s.size++] = w;
    bool inside = false;
    switch (s.size) {
      case 2: v = closest_on_segment(s); break;
      case 3: v = closest_on_triangle(s); break;
      default: v = closest_on_tetrahedron(s, inside); break;
    }
    if (inside) {
      out.intersecting = true;
      out.lower = out.upper = 0.0;
      return out;
    }
  }
  out.upper = glm::length(v);
  return out;
}

}  // namespace steady
