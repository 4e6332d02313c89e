#include "steady/properties/mass_moments.hpp"

#include <cmath>

namespace steady {

MassMoments& MassMoments::operator+=(const MassMoments& o) {
  volume += o.volume;
  first += o.first;
  second += o.second;
  area += o.area;
  return *this;
}

MassMoments& MassMoments::operator-=(const MassMoments& o) {
  volume -= o.volume;
  first -= o.first;
  second -= o.second;
  area -= o.area;
  return *this;
}

MassMoments MassMoments::scaled(double factor) const {
  MassMoments m = *this;
  m.volume *= factor;
  m.first *= factor;
  m.second *= factor;
  m.area *= factor;
  return m;
}

MassMoments transformed(const MassMoments& m, const SimilarityTransform& t) {
  // x' = s R x + t:  int x' dV' = s^3 (s R f + V t);
  // int x' x'^T dV' = s^3 (s^2 R S R^T + s (R f) t^T + s t (R f)^T + V t t^T).
  const double s = t.scale, s3 = s * s * s;
  const Vec3 rf = t.rotation * m.first;
  MassMoments out;
  out.volume = s3 * m.volume;
  out.first = s3 * (s * rf + m.volume * t.translation);
  const Mat3 cross = glm::outerProduct(rf, t.translation);
  out.second = s3 * (s * s * (t.rotation * m.second * glm::transpose(t.rotation)) + s * (cross + glm::transpose(cross)) +
                     m.volume * glm::outerProduct(t.translation, t.translation));
  out.area = s * s * m.area;
  return out;
}

MassMoments about(const MassMoments& m, const Vec3& origin) {
  SimilarityTransform shift;
  shift.translation = -origin;
  return transformed(m, shift);
}

MassMoments axisymmetric_moments(const Vec3& axis, double volume, double axial_first, double axial_second,
                                 double radial_second, double area) {
  MassMoments m;
  m.volume = volume;
  m.first = axial_first * axis;
  const Mat3 nn = glm::outerProduct(axis, axis);
  // The radial part spreads evenly over the two directions across the axis.
  m.second = axial_second * nn + (0.5 * radial_second) * (Mat3(1.0) - nn);
  m.area = area;
  return m;
}

Vec3 centroid(const MassMoments& m) { return m.first / m.volume; }

Mat3 central_second_moment(const MassMoments& m) {
  const Vec3 c = centroid(m);
  return m.second - m.volume * glm::outerProduct(c, c);
}

Mat3 central_inertia(const MassMoments& m) {
  const Mat3 s = central_second_moment(m);
  const double trace = s[0][0] + s[1][1] + s[2][2];
  return trace * Mat3(1.0) - s;
}

bool is_finite(const MassMoments& m) {
  bool ok = std::isfinite(m.volume) && std::isfinite(m.area);
  for (int i = 0; i < 3; ++i) {
    ok = ok && std::isfinite(m.first[i]);
    for (int j = 0; j < 3; ++j) ok = ok && std::isfinite(m.second[i][j]);
  }
  return ok;
}

}  // namespace steady
