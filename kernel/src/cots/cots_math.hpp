#pragma once
// Internal: the small pieces of complex and real arithmetic the COTS and BeCOTS maps share, each written so that it
// stays accurate where the textbook formula cancels (the parallelogram and cylinder limits, where logs go to 0).
#include <cmath>
#include <complex>

#include "core/similarity_generator.hpp"

namespace steady::cots_detail {

using Complex = std::complex<double>;

constexpr double kTwoPi = 6.283185307179586476925286766559;

// ln(1 + w), principal (imaginary part in (-pi, pi]), accurate for small |w|. A negative zero imaginary part is
// read as +0, so that the anti-parallel case (1 + w real negative) always takes the angle +pi.
inline Complex log1p(Complex w) {
  const double re = w.real();
  const double im = w.imag() == 0.0 ? 0.0 : w.imag();
  if (std::abs(w) >= 0.5) return std::log(Complex(1.0 + re, im));
  // |1 + w|^2 - 1 = 2 re + re^2 + im^2, without forming 1 + ...
  return {0.5 * std::log1p(2.0 * re + re * re + im * im), std::atan2(im, 1.0 + re)};
}

// (e^z - 1)/z, continuous at 0; real and complex.
inline double phi(double x) { return detail::expm1_ratio(x); }
inline Complex phi(Complex z) { return detail::expm1_ratio(z); }

// log1p(x)/x, continuous at 0 (value 1).
inline double log1p_ratio(double x) { return x == 0.0 ? 1.0 : std::log1p(x) / x; }

// The integral of e^{2 l t} over t in [0, h]: (e^{2 l h} - 1)/(2 l), = h at l = 0.
inline double exp2_integral(double l, double h) { return h * phi(2.0 * l * h); }

// Im(conj(p) q): the cross product of two plane vectors written as complex numbers.
inline double cross(Complex p, Complex q) { return p.real() * q.imag() - p.imag() * q.real(); }

// The branches k (angles arg + 2 pi k) whose angle can fall in [alpha_min, alpha_max], one more on each side so
// that rounding at a window's end never loses a pre-image (the caller filters the solutions anyway).
inline void branch_range(double alpha0, double alpha_min, double alpha_max, long* first, long* last) {
  *first = static_cast<long>(std::floor((alpha_min - alpha0) / kTwoPi)) - 1;
  *last = static_cast<long>(std::ceil((alpha_max - alpha0) / kTwoPi)) + 1;
}

}  // namespace steady::cots_detail
