#pragma once
// Internal: the functions that map a similarity generator to its group element and back.
// Shared by the 3D and 2D similarities. The in-plane part of a 3D similarity (and the whole of a 2D one)
// is complex multiplication: rotation by alpha with log-scale sigma is multiplication by e^L, L = sigma + i alpha.
#include <complex>

namespace steady::detail {

using Complex = std::complex<double>;

// expm1(x) / x, continuous at 0 (value 1).
double expm1_ratio(double x);

// (e^L - 1) / L for complex L, continuous at 0 (value 1), accurate for small |L| and for L near the
// unit circle's integer-turn points where e^L - 1 cancels.
Complex expm1_ratio(Complex L);

}  // namespace steady::detail
