#include "steady/core/similarity.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <sstream>

#include "core/similarity_generator.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/numeric_range.hpp"
#include "steady/core/rotation.hpp"
#include "steady/core/tolerance.hpp"

namespace steady {
namespace {

using detail::Complex;

void require_finite_vec(const Vec3& v, const std::string& field) {
  for (int c = 0; c < 3; ++c) require_finite(v[c], field);
}

Vec3 unit_axis(const Vec3& axis, const char* field) {
  require_finite_vec(axis, field);
  // Scaled by its largest component first: |axis| of huge components would overflow, of tiny ones underflow.
  const double largest = std::max({std::abs(axis.x), std::abs(axis.y), std::abs(axis.z)});
  if (!(largest > 0.0)) fail_input(field, "the axis must be a non-zero vector");
  const Vec3 scaled = axis / largest;
  return scaled / glm::length(scaled);
}

// Rotation by |omega| about omega / |omega|.
Mat3 rotation_from_vector(const Vec3& omega) {
  const double angle = glm::length(omega);
  if (angle == 0.0) return Mat3(1.0);
  return axis_rotation(omega / angle, std::cos(angle), std::sin(angle));
}

// The principal rotation vector (angle in [0, pi]) of an orthonormal matrix.
Vec3 rotation_vector_from_matrix(const Mat3& r) {
  glm::dquat q = glm::normalize(glm::quat_cast(r));
  if (q.w < 0.0) q = -q;
  const Vec3 xyz(q.x, q.y, q.z);
  const double sin_half = glm::length(xyz);
  if (sin_half == 0.0) return Vec3(0.0);
  const double angle = 2.0 * std::atan2(sin_half, q.w);
  return xyz * (angle / sin_half);
}

// The translation t of exp(sigma, omega, v): t = J v, with J = integral_0^1 exp(tau (sigma + [omega]x)) dtau.
// Along the axis J is expm1(sigma)/sigma; across it, multiplication by (e^L - 1)/L, L = sigma + i angle.
Vec3 translation_from_generator(double sigma, const Vec3& omega, const Vec3& v) {
  const double angle = glm::length(omega);
  if (angle == 0.0) return detail::expm1_ratio(sigma) * v;
  const Vec3 n = omega / angle;
  const Vec3 along = glm::dot(v, n) * n;
  const Vec3 across = v - along;
  const Complex psi = detail::expm1_ratio(Complex(sigma, angle));
  return detail::expm1_ratio(sigma) * along + psi.real() * across + psi.imag() * glm::cross(n, across);
}

// The inverse of translation_from_generator: v = J^-1 t.
Vec3 velocity_from_translation(double sigma, const Vec3& omega, const Vec3& t) {
  const double angle = glm::length(omega);
  if (angle == 0.0) return t / detail::expm1_ratio(sigma);
  const Vec3 n = omega / angle;
  const Vec3 along = glm::dot(t, n) * n;
  const Vec3 across = t - along;
  const Complex inv_psi = 1.0 / detail::expm1_ratio(Complex(sigma, angle));
  return along / detail::expm1_ratio(sigma) + inv_psi.real() * across + inv_psi.imag() * glm::cross(n, across);
}

double max_abs_difference(const Mat3& a, const Mat3& b) {
  double m = 0.0;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m = std::max(m, std::abs(a[c][r] - b[c][r]));
  return m;
}

void validate_rotation_matrix(const Mat3& r, const char* field) {
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) require_finite(r[c][k], field);
  const double err = max_abs_difference(glm::transpose(r) * r, Mat3(1.0));
  if (err > kFrameTolerance) fail_input(field, "the rotation matrix is not orthonormal");
  if (glm::determinant(r) <= 0.0) fail_input(field, "the rotation matrix is a reflection (determinant <= 0)");
}

}  // namespace

const char* to_string(SimilarityKind kind) {
  switch (kind) {
    case SimilarityKind::Identity: return "identity";
    case SimilarityKind::Translation: return "translation";
    case SimilarityKind::Rotation: return "rotation";
    case SimilarityKind::Screw: return "screw";
    case SimilarityKind::Dilation: return "dilation";
    case SimilarityKind::Swirl: return "swirl";
  }
  return "unknown";
}

Similarity::Similarity() = default;

void Similarity::cache_group_element() {
  scale_ = std::exp(log_scale_);
  rotation_ = rotation_from_vector(rotation_vector_);
  translation_ = translation_from_generator(log_scale_, rotation_vector_, velocity_);
  require_within(translation_, kMaxCoordinate, "similarity: its translation");
}

Similarity Similarity::identity() { return Similarity(); }

Similarity Similarity::from_generator(double log_scale, const Vec3& rotation_vector, const Vec3& velocity) {
  // Every similarity is made here: its range is checked once (numeric_range.hpp).
  require_within(log_scale, kMaxLogScale, "log_scale");
  require_finite_vec(rotation_vector, "rotation_vector");
  if (!(glm::length(rotation_vector) <= kMaxAngle))
    fail_input("rotation_vector", "its angle " + std::to_string(glm::length(rotation_vector)) +
                                      " rad is beyond the supported range of " + std::to_string(kMaxAngle) + " rad");
  require_within(velocity, kMaxCoordinate * std::max(1.0, std::abs(log_scale) + glm::length(rotation_vector)),
                 "velocity");
  Similarity s;
  s.log_scale_ = log_scale;
  s.rotation_vector_ = rotation_vector;
  s.velocity_ = velocity;
  s.cache_group_element();
  return s;
}

Similarity Similarity::translation(const Vec3& vector) {
  require_within(vector, kMaxCoordinate, "translation.vector");
  return from_generator(0.0, Vec3(0.0), vector);
}

Similarity Similarity::rotation(double angle, const Vec3& axis, const Vec3& point) {
  require_within(angle, kMaxAngle, "rotation.angle");
  require_within(point, kMaxCoordinate, "rotation.point");
  const Vec3 omega = angle * unit_axis(axis, "rotation.axis");
  // The velocity field of a rotation about the line through `point`: v(p) = omega x (p - point).
  return from_generator(0.0, omega, -glm::cross(omega, point));
}

Similarity Similarity::dilation(double scale, const Vec3& center) {
  require_positive(scale, "dilation.scale");
  require_within(std::log(scale), kMaxLogScale, "dilation.scale (its logarithm)");
  require_within(center, kMaxCoordinate, "dilation.center");
  const double sigma = std::log(scale);
  return from_generator(sigma, Vec3(0.0), -sigma * center);
}

Similarity Similarity::screw(double angle, const Vec3& axis, const Vec3& point, double distance) {
  require_within(angle, kMaxAngle, "screw.angle");
  require_within(distance, kMaxCoordinate, "screw.distance");
  require_within(point, kMaxCoordinate, "screw.point");
  const Vec3 n = unit_axis(axis, "screw.axis");
  const Vec3 omega = angle * n;
  return from_generator(0.0, omega, -glm::cross(omega, point) + distance * n);
}

Similarity Similarity::swirl(double angle, const Vec3& axis, const Vec3& center, double scale) {
  require_within(angle, kMaxAngle, "swirl.angle");
  require_positive(scale, "swirl.scale");
  require_within(std::log(scale), kMaxLogScale, "swirl.scale (its logarithm)");
  require_within(center, kMaxCoordinate, "swirl.center");
  const Vec3 omega = angle * unit_axis(axis, "swirl.axis");
  const double sigma = std::log(scale);
  // The generator vanishes at the fixed point: sigma c + omega x c + v = 0.
  return from_generator(sigma, omega, -(sigma * center + glm::cross(omega, center)));
}

Similarity Similarity::from_matrix(double scale, const Mat3& rotation, const Vec3& translation) {
  require_positive(scale, "scale");
  require_within(std::log(scale), kMaxLogScale, "scale (its logarithm)");
  require_within(translation, kMaxCoordinate, "translation");
  validate_rotation_matrix(rotation, "rotation");
  const double sigma = std::log(scale);
  const Vec3 omega = rotation_vector_from_matrix(rotation);
  return from_generator(sigma, omega, velocity_from_translation(sigma, omega, translation));
}

Similarity Similarity::from_transform(const SimilarityTransform& t) {
  return from_matrix(t.scale, t.rotation, t.translation);
}

Similarity Similarity::from_frame(const Frame& f) {
  validate_frame(f, "frame");
  const double s = glm::length(f.x);
  // Re-orthonormalise through the quaternion so that tiny input errors do not leak into the rotation.
  const Mat3 basis(f.x / s, f.y / s, f.z / s);
  const Mat3 r = glm::mat3_cast(glm::normalize(glm::quat_cast(basis)));
  return from_matrix(s, r, f.origin);
}

Similarity Similarity::from_frames(const Frame& a, const Frame& b) {
  // Compose in matrix form and take the principal logarithm: the answer must not depend on the windings
  // of the two frames' own generators.
  return from_transform(from_frame(b).transform() * from_frame(a).inverse().transform());
}

Similarity Similarity::operator*(const Similarity& rhs) const {
  const double s = scale_ * rhs.scale_;
  const Mat3 r = rotation_ * rhs.rotation_;
  const Vec3 t = scale_ * (rotation_ * rhs.translation_) + translation_;
  // Commuting generators add exactly (exp(a) exp(b) = exp(a + b)), which keeps windings: S * S^t,
  // rotations about one line, a similarity and a dilation about its own fixed point...
  const double wa = glm::length(rotation_vector_), wb = glm::length(rhs.rotation_vector_);
  if (glm::length(glm::cross(rotation_vector_, rhs.rotation_vector_)) <= kCommuteTolerance * wa * wb) {
    Similarity sum = from_generator(log_scale_ + rhs.log_scale_, rotation_vector_ + rhs.rotation_vector_,
                                    velocity_ + rhs.velocity_);
    // The velocities enter the floor because a winding rotation (2 pi about a line off the origin) has
    // no translation yet a non-zero velocity.
    const double length_scale = glm::length(translation_) + scale_ * glm::length(rhs.translation_) +
                                glm::length(velocity_) + glm::length(rhs.velocity_);
    if (std::abs(sum.scale_ - s) <= kCommuteTolerance * s &&
        max_abs_difference(sum.rotation_, r) <= kCommuteTolerance &&
        glm::length(sum.translation_ - t) <= kCommuteTolerance * length_scale)
      return sum;
  }
  return from_matrix(s, r, t);
}

Similarity Similarity::inverse() const { return from_generator(-log_scale_, -rotation_vector_, -velocity_); }

Similarity Similarity::power(double t) const {
  require_finite(t, "power exponent");
  return from_generator(t * log_scale_, t * rotation_vector_, t * velocity_);
}

Frame Similarity::frame() const {
  return Frame{translation_, scale_ * rotation_[0], scale_ * rotation_[1], scale_ * rotation_[2]};
}

CanonicalForm Similarity::canonical() const {
  CanonicalForm c;
  const double sigma = log_scale_;
  const double angle = glm::length(rotation_vector_);
  const bool rotates = angle > kAngleTolerance;
  const bool scales = std::abs(sigma) > kLogScaleTolerance;
  c.scale = scale_;
  if (!rotates && !scales) {
    c.translation = translation_;
    c.kind = glm::length(translation_) > kLengthTolerance ? SimilarityKind::Translation : SimilarityKind::Identity;
    return c;
  }
  if (!rotates) {  // dilation: the generator sigma p + v vanishes at p = -v / sigma
    c.kind = SimilarityKind::Dilation;
    c.point = -velocity_ / sigma;
    return c;
  }
  const Vec3 n = rotation_vector_ / angle;
  c.angle = angle;
  c.axis = n;
  const Vec3 along = glm::dot(velocity_, n) * n;
  const Vec3 across = velocity_ - along;
  if (!scales) {  // rotation or screw: the axis point closest to the origin solves omega x F = -across
    c.point = glm::cross(rotation_vector_, velocity_) / (angle * angle);
    c.distance = glm::dot(velocity_, n);
    c.kind = std::abs(c.distance) > kLengthTolerance ? SimilarityKind::Screw : SimilarityKind::Rotation;
    return c;
  }
  // swirl: (sigma + [omega]x) F = -v, solved along the axis and, as a complex division, across it.
  c.kind = SimilarityKind::Swirl;
  const Vec3 f_along = -along / sigma;
  const double denom = sigma * sigma + angle * angle;
  const Vec3 f_across = -(sigma * across - angle * glm::cross(n, across)) / denom;
  c.point = f_along + f_across;
  return c;
}

std::string Similarity::describe() const {
  const CanonicalForm c = canonical();
  std::ostringstream os;
  os.precision(6);
  auto vec = [&os](const Vec3& v) { os << "(" << v.x << ", " << v.y << ", " << v.z << ")"; };
  os << to_string(c.kind);
  switch (c.kind) {
    case SimilarityKind::Identity: break;
    case SimilarityKind::Translation: os << " by "; vec(c.translation); break;
    case SimilarityKind::Dilation: os << " by " << c.scale << " about "; vec(c.point); break;
    case SimilarityKind::Rotation:
    case SimilarityKind::Screw:
    case SimilarityKind::Swirl:
      os << " by " << c.angle << " rad about axis "; vec(c.axis);
      os << " through "; vec(c.point);
      if (c.kind == SimilarityKind::Screw) os << ", advancing " << c.distance;
      if (c.kind == SimilarityKind::Swirl) os << ", scale " << c.scale;
      break;
  }
  return os.str();
}

double Similarity::map_distance(const Similarity& other) const {
  double d = glm::length(translation_ - other.translation_);
  for (int c = 0; c < 3; ++c) {
    Vec3 e(0.0);
    e[c] = 1.0;
    d = std::max(d, glm::length(apply_point(e) - other.apply_point(e)));
  }
  return d;
}

bool Similarity::approx_equal(const Similarity& other, double tolerance, const Vec3& center,
                              double radius) const {
  // An affine map's largest displacement over a ball is at the center plus radius times the largest
  // singular value of the linear part difference, bounded by its Frobenius norm.
  const Vec3 dc = apply_point(center) - other.apply_point(center);
  const Mat3 dl = scale_ * rotation_ - other.scale_ * other.rotation_;
  double frob = 0.0;
  for (int c = 0; c < 3; ++c) frob += glm::dot(dl[c], dl[c]);
  const double bound = glm::length(dc) + radius * std::sqrt(frob);
  return bound <= tolerance * (1.0 + radius + glm::length(center));
}

void validate_frame(const Frame& f, const char* field) {
  const std::string name(field);
  require_finite_vec(f.origin, name + ".origin");
  require_finite_vec(f.x, name + ".x");
  require_finite_vec(f.y, name + ".y");
  require_finite_vec(f.z, name + ".z");
  const double s = glm::length(f.x);
  if (!(s > 0.0)) fail_input(name + ".x", "the frame's x axis must be a non-zero vector");
  const double tol = kFrameTolerance * s;
  if (std::abs(glm::length(f.y) - s) > tol || std::abs(glm::length(f.z) - s) > tol)
    fail_input(name, "|x|, |y| and |z| must be equal (the frame's scale)");
  if (std::abs(glm::dot(f.x, f.y)) > tol * s || std::abs(glm::dot(f.y, f.z)) > tol * s ||
      std::abs(glm::dot(f.z, f.x)) > tol * s)
    fail_input(name, "x, y and z must be pairwise orthogonal");
  if (glm::dot(glm::cross(f.x, f.y), f.z) <= 0.0) fail_input(name, "x, y, z must be right-handed (z = x cross y / |x|)");
}

}  // namespace steady
