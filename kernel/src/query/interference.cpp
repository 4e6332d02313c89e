#include "steady/query/interference.hpp"

#include <algorithm>
#include <cmath>

namespace steady {

double distance_to_ball(const Vec3& p, const Ball& ball) { return glm::length(p - ball.center) - ball.radius; }

double distance_to_hull(const Vec3& p, const Ball& a, const Ball& b) {
  const Vec3 d = b.center - a.center;
  const double length = glm::length(d);
  // One ball inside the other (this includes length 0): the hull is the larger ball.
  if (length <= std::abs(a.radius - b.radius)) return distance_to_ball(p, a.radius >= b.radius ? a : b);
  const Vec3 axis = d / length;
  const Vec3 w = p - a.center;
  const double x = glm::dot(w, axis);
  const double y = std::sqrt(std::max(0.0, glm::dot(w, w) - x * x));
  const double sin_phi = (a.radius - b.radius) / length;
  const double cos_phi = std::sqrt((1.0 - sin_phi) * (1.0 + sin_phi));
  // Coordinate of p along the cone's generator, 0 at the tangent circle of a, length cos(phi) at b's.
  const double t = x * cos_phi - y * sin_phi;
  if (t < 0.0) return glm::length(w) - a.radius;
  if (t > length * cos_phi) return glm::length(p - b.center) - b.radius;
  return x * sin_phi + y * cos_phi - a.radius;
}

double ray_enters_ball(const Vec3& origin, const Vec3& direction, const Ball& ball) {
  const Vec3 w = origin - ball.center;
  const double c = glm::dot(w, w) - ball.radius * ball.radius;
  if (c <= 0.0) return 0.0;
  const double b = glm::dot(w, direction);
  if (b >= 0.0) return kNoHit;  // outside and moving away
  const double disc = b * b - c;
  if (disc < 0.0) return kNoHit;
  // The nearer root, in the cancellation-free form c / (-b + sqrt(disc)).
  return c / (-b + std::sqrt(disc));
}

namespace {

// Least s >= 0 where the ray meets the lateral cone of the hull between its two tangent circles.
double ray_enters_cone(const Vec3& origin, const Vec3& direction, const Ball& a, const Vec3& axis, double length,
                       double sin_phi, double cos_phi) {
  const Vec3 w0 = origin - a.center;
  const double x0 = glm::dot(w0, axis), dx = glm::dot(direction, axis);
  const Vec3 w0p = w0 - x0 * axis, dp = direction - dx * axis;
  // On the cone: y cos(phi) = ra - x sin(phi) with y the distance to the axis; squared, a quadratic in s.
  const double c0 = a.radius - x0 * sin_phi, c1 = dx * sin_phi;
  const double cos2 = cos_phi * cos_phi;
  const double qa = glm::dot(dp, dp) * cos2 - c1 * c1;
  const double qb = glm::dot(w0p, dp) * cos2 + c0 * c1;
  const double qc = glm::dot(w0p, w0p) * cos2 - c0 * c0;
  double roots[2];
  int count = 0;
  if (std::abs(qa) <= 1e-14 * (glm::dot(dp, dp) * cos2 + c1 * c1) || qa == 0.0) {
    if (qb != 0.0) roots[count++] = -qc / (2.0 * qb);
  } else {
    const double disc = qb * qb - qa * qc;
    if (disc < 0.0) return kNoHit;
    const double sq = std::sqrt(disc);
    // Stable pair of roots.
    const double q = -(qb + std::copysign(sq, qb));
    roots[count++] = q / qa;
    if (q != 0.0) roots[count++] = qc / q;
  }
  double best = kNoHit;
  for (int r = 0; r < count; ++r) {
    const double s = roots[r];
    if (!(s >= 0.0) || s >= best) continue;
    const double rhs = c0 - s * c1;  // y cos(phi): must be >= 0 (the squaring added the mirrored cone)
    if (rhs < 0.0) continue;
    const double x = x0 + s * dx, y = rhs / cos_phi;
    const double t = x * cos_phi - y * sin_phi;
    if (t < 0.0 || t > length * cos_phi) continue;
    best = s;
  }
  return best;
}

}  // namespace

double ray_enters_hull(const Vec3& origin, const Vec3& direction, const Ball& a, const Ball& b) {
  const Vec3 d = b.center - a.center;
  const double length = glm::length(d);
  if (length <= std::abs(a.radius - b.radius))
    return ray_enters_ball(origin, direction, a.radius >= b.radius ? a : b);
  if (distance_to_hull(origin, a, b) <= 0.0) return 0.0;
  const Vec3 axis = d / length;
  const double sin_phi = (a.radius - b.radius) / length;
  const double cos_phi = std::sqrt((1.0 - sin_phi) * (1.0 + sin_phi));
  double best = std::min(ray_enters_ball(origin, direction, a), ray_enters_ball(origin, direction, b));
  best = std::min(best, ray_enters_cone(origin, direction, a, axis, length, sin_phi, cos_phi));
  return best;
}

}  // namespace steady
