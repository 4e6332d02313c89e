#pragma once
// Internal: distances between points and segments, for the capsule tests (a capsule is the set within a radius of
// a segment) of the bridges' routes and the connectors' clashes.
#include <algorithm>

#include "steady/core/vec.hpp"

namespace steady {

// From p to the segment [a, b] (a point when a == b).
inline double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

// The least distance between segments [a0, a1] and [b0, b1]: the minimum over the interior critical point (when
// the lines are not parallel and it falls inside both) and the four endpoint-to-segment distances.
inline double segment_distance(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
  double best = std::min({point_segment_distance(a0, b0, b1), point_segment_distance(a1, b0, b1),
                          point_segment_distance(b0, a0, a1), point_segment_distance(b1, a0, a1)});
  const Vec3 u = a1 - a0, v = b1 - b0, w = a0 - b0;
  const double uu = glm::dot(u, u), uv = glm::dot(u, v), vv = glm::dot(v, v), uw = glm::dot(u, w), vw = glm::dot(v, w);
  const double det = uu * vv - uv * uv;
  if (det > 1e-12 * uu * vv) {
    const double s = (uv * vw - vv * uw) / det, t = (uu * vw - uv * uw) / det;
    if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) best = std::min(best, glm::length(w + s * u - t * v));
  }
  return best;
}

}  // namespace steady
