#include "steady/properties/similar_copies.hpp"

#include <cmath>

namespace steady {

SimilarityTransform transform_about(const SimilarityTransform& t, const Vec3& origin) {
  SimilarityTransform out = t;
  out.translation = t.apply_point(origin) - origin;
  return out;
}

SimilarityTransform transform_about(const Similarity& s, const Vec3& origin) {
  return transform_about(s.transform(), origin);
}

namespace {

// S(count) = sum_{k < count} T^k X by doubling on the bits of count.
MassMoments doubling_sum(const Similarity& step, const Vec3& origin, const MassMoments& body, std::int64_t count) {
  if (count <= 0) return {};
  if (count == 1) return body;
  const std::int64_t half = count / 2;
  const MassMoments h = doubling_sum(step, origin, body, half);
  MassMoments out = h + transformed(h, transform_about(step.power(static_cast<double>(half)), origin));
  if (count % 2 == 1)
    out += transformed(body, transform_about(step.power(static_cast<double>(2 * half)), origin));
  return out;
}

}  // namespace

MassMoments sum_of_copies(const Similarity& step, const Vec3& origin, const MassMoments& body, std::int64_t count,
                          std::int64_t first) {
  const MassMoments s = doubling_sum(step, origin, body, count);
  if (first == 0) return s;
  return transformed(s, transform_about(step.power(static_cast<double>(first)), origin));
}

double geometric_sum(double log_ratio, std::int64_t count) {
  if (count <= 0) return 0.0;
  if (log_ratio == 0.0) return static_cast<double>(count);
  return std::expm1(static_cast<double>(count) * log_ratio) / std::expm1(log_ratio);
}

bool exactly_commute(const Similarity& a, const Similarity& b) {
  // The Lie bracket of the generators (sigma, omega, v): [(s1, w1, v1), (s2, w2, v2)] =
  // (0, w1 x w2, w1 x v2 - w2 x v1 + s1 v2 - s2 v1). Zero (computed exactly zero) means the one-parameter
  // groups commute, so every power of a commutes with every power of b up to the rounding of the powers.
  const Vec3& w1 = a.rotation_vector();
  const Vec3& w2 = b.rotation_vector();
  const Vec3 rotation_part = glm::cross(w1, w2);
  const Vec3 translation_part = glm::cross(w1, b.velocity()) - glm::cross(w2, a.velocity()) +
                                a.log_scale() * b.velocity() - b.log_scale() * a.velocity();
  return rotation_part == Vec3(0.0) && translation_part == Vec3(0.0);
}

}  // namespace steady
