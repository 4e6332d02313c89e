#include "steady/similar_copies.hpp"

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
  auto identity = [](const Similarity& s) {
    return s.log_scale() == 0.0 && s.rotation_vector() == Vec3(0.0) && s.velocity() == Vec3(0.0);
  };
  auto translation = [](const Similarity& s) { return s.log_scale() == 0.0 && s.rotation_vector() == Vec3(0.0); };
  if (identity(a) || identity(b)) return true;
  if (translation(a) && translation(b)) return true;
  return a.log_scale() == b.log_scale() && a.rotation_vector() == b.rotation_vector() && a.velocity() == b.velocity();
}

}  // namespace steady
