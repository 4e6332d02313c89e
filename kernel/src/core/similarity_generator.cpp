#include "core/similarity_generator.hpp"

#include <cmath>

namespace steady::detail {

double expm1_ratio(double x) { return x == 0.0 ? 1.0 : std::expm1(x) / x; }

Complex expm1_ratio(Complex L) {
  const double sigma = L.real();
  const double alpha = L.imag();
  if (sigma == 0.0 && alpha == 0.0) return 1.0;
  // e^L - 1 = (e^sigma cos a - 1) + i e^sigma sin a, with the real part written without cancellation:
  // e^sigma cos a - 1 = expm1(sigma) cos a - 2 sin^2(a/2).
  const double half_sin = std::sin(0.5 * alpha);
  const double re = std::expm1(sigma) * std::cos(alpha) - 2.0 * half_sin * half_sin;
  const double im = std::exp(sigma) * std::sin(alpha);
  return Complex(re, im) / L;
}

}  // namespace steady::detail
