#pragma once
// The real roots of a t^2 + 2 b t + c = 0 (a line's crossings of a quadric), in the stable form; a nearly
// vanishing `a` leaves the linear equation's root.
#include <cmath>
#include <vector>

namespace steady {

inline void quadratic_roots(double a, double b, double c, std::vector<double>& out) {
  if (std::abs(a) <= 1e-14 * (std::abs(b) + std::abs(c)) + 1e-300) {
    if (b != 0.0) out.push_back(-0.5 * c / b);
    return;
  }
  const double disc = b * b - a * c;
  if (disc < 0.0) return;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  out.push_back(q / a);
  if (q != 0.0) out.push_back(c / q);
}

}  // namespace steady
