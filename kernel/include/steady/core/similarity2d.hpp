#pragma once
// Orientation-preserving similarities of the plane: z -> a z + b in complex form (a = s e^{i alpha}).
// Stored, like the 3D similarity, by the generator (L = ln s + i alpha, w) so that real powers are exact
// and uniform: S^t = exp(t L, t w).
#include <complex>

#include "steady/core/vec.hpp"

namespace steady {

enum class Similarity2Kind { Identity, Translation, Rotation, Dilation, Spiral };
const char* to_string(Similarity2Kind kind);

class Similarity2 {
 public:
  using Complex = std::complex<double>;
  Similarity2();  // identity

  static Similarity2 translation(const Vec2& vector);
  static Similarity2 spiral(double angle, double scale, const Vec2& center);  // rotation + dilation about center
  static Similarity2 from_generator(Complex log_multiplier, Complex velocity);
  static Similarity2 from_complex(Complex a, Complex b);  // z -> a z + b, principal angle in (-pi, pi]
  // The similarity taking A to C and B to D (A != B, C != D).
  static Similarity2 from_point_pairs(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d);

  Similarity2 operator*(const Similarity2& rhs) const;  // apply rhs first
  Similarity2 inverse() const;
  Similarity2 power(double t) const;
  Vec2 apply(const Vec2& p) const;

  double scale() const { return std::abs(a_); }
  double angle() const { return log_multiplier_.imag(); }
  Complex multiplier() const { return a_; }
  // The generator: S = exp(L, w), z -> e^L z + (e^L - 1) / L w.
  Complex log_multiplier() const { return log_multiplier_; }
  Complex velocity() const { return velocity_; }
  Complex offset() const { return b_; }
  Similarity2Kind kind() const;
  // The fixed point (rotation, dilation, spiral); throws for translations and the identity.
  Vec2 fixed_point() const;

 private:
  Complex log_multiplier_{0.0, 0.0};
  Complex velocity_{0.0, 0.0};
  Complex a_{1.0, 0.0};
  Complex b_{0.0, 0.0};
};

}  // namespace steady
