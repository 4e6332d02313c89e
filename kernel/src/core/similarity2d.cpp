#include "steady/core/similarity2d.hpp"

#include <cmath>

#include "core/similarity_generator.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/tolerance.hpp"

namespace steady {
namespace {
using Complex = std::complex<double>;
Complex to_complex(const Vec2& p) { return {p.x, p.y}; }
Vec2 to_vec(Complex z) { return {z.real(), z.imag()}; }
void require_finite2(const Vec2& p, const char* field) {
  require_finite(p.x, field);
  require_finite(p.y, field);
}
}  // namespace

const char* to_string(Similarity2Kind kind) {
  switch (kind) {
    case Similarity2Kind::Identity: return "identity";
    case Similarity2Kind::Translation: return "translation";
    case Similarity2Kind::Rotation: return "rotation";
    case Similarity2Kind::Dilation: return "dilation";
    case Similarity2Kind::Spiral: return "spiral";
  }
  return "unknown";
}

Similarity2::Similarity2() = default;

Similarity2 Similarity2::from_generator(Complex log_multiplier, Complex velocity) {
  require_finite(log_multiplier.real(), "log_scale");
  require_finite(log_multiplier.imag(), "angle");
  require_finite(velocity.real(), "velocity");
  require_finite(velocity.imag(), "velocity");
  Similarity2 s;
  s.log_multiplier_ = log_multiplier;
  s.velocity_ = velocity;
  s.a_ = std::exp(log_multiplier);
  s.b_ = detail::expm1_ratio(log_multiplier) * velocity;
  return s;
}

Similarity2 Similarity2::translation(const Vec2& vector) {
  require_finite2(vector, "translation.vector");
  return from_generator(0.0, to_complex(vector));
}

Similarity2 Similarity2::spiral(double angle, double scale, const Vec2& center) {
  require_finite(angle, "spiral.angle");
  require_positive(scale, "spiral.scale");
  require_finite2(center, "spiral.center");
  const Complex L(std::log(scale), angle);
  return from_generator(L, -L * to_complex(center));  // the generator L z + w vanishes at the center
}

Similarity2 Similarity2::from_complex(Complex a, Complex b) {
  if (!(std::abs(a) > 0.0) || !std::isfinite(std::abs(a))) fail_input("multiplier", "must be a finite non-zero complex number");
  require_finite(b.real(), "offset");
  require_finite(b.imag(), "offset");
  const Complex L = std::log(a);  // principal: angle in (-pi, pi]
  return from_generator(L, b / detail::expm1_ratio(L));
}

Similarity2 Similarity2::from_point_pairs(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  require_finite2(a, "A");
  require_finite2(b, "B");
  require_finite2(c, "C");
  require_finite2(d, "D");
  const Complex ab = to_complex(b) - to_complex(a), cd = to_complex(d) - to_complex(c);
  if (ab == 0.0) fail_input("A, B", "the first pair must be two distinct points");
  if (cd == 0.0) fail_input("C, D", "the second pair must be two distinct points");
  const Complex m = cd / ab;
  return from_complex(m, to_complex(c) - m * to_complex(a));
}

Similarity2 Similarity2::operator*(const Similarity2& rhs) const {
  // Generators of the plane's similarities commute exactly when they share a fixed point (or both are
  // translations); their sum then keeps the winding of the angles.
  const Complex a = a_ * rhs.a_, b = a_ * rhs.b_ + b_;
  const Similarity2 sum = from_generator(log_multiplier_ + rhs.log_multiplier_, velocity_ + rhs.velocity_);
  const double floor = std::abs(b_) + std::abs(a_) * std::abs(rhs.b_) + std::abs(velocity_) + std::abs(rhs.velocity_);
  if (std::abs(sum.a_ - a) <= kCommuteTolerance * std::abs(a) && std::abs(sum.b_ - b) <= kCommuteTolerance * floor)
    return sum;
  return from_complex(a, b);
}

Similarity2 Similarity2::inverse() const { return from_generator(-log_multiplier_, -velocity_); }

Similarity2 Similarity2::power(double t) const {
  require_finite(t, "power exponent");
  return from_generator(t * log_multiplier_, t * velocity_);
}

Vec2 Similarity2::apply(const Vec2& p) const { return to_vec(a_ * to_complex(p) + b_); }

Similarity2Kind Similarity2::kind() const {
  const bool rotates = std::abs(log_multiplier_.imag()) > kAngleTolerance;
  const bool scales = std::abs(log_multiplier_.real()) > kLogScaleTolerance;
  if (rotates && scales) return Similarity2Kind::Spiral;
  if (rotates) return Similarity2Kind::Rotation;
  if (scales) return Similarity2Kind::Dilation;
  return std::abs(b_) > kLengthTolerance ? Similarity2Kind::Translation : Similarity2Kind::Identity;
}

Vec2 Similarity2::fixed_point() const {
  const Similarity2Kind k = kind();
  if (k == Similarity2Kind::Identity || k == Similarity2Kind::Translation)
    fail_input("fixed_point", std::string("a ") + to_string(k) + " has no fixed point");
  return to_vec(-velocity_ / log_multiplier_);
}

}  // namespace steady
