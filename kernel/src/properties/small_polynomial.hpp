#pragma once
// Real polynomials of degree at most 4 (coefficients c[0] + c[1] x + ... + c[4] x^4) and their real roots
// in an interval, by isolating them between the roots of the derivative (recursively) and bisecting each
// sign change to the last bit. Roots of even multiplicity (no sign change) are not reported.
#include <array>
#include <cmath>
#include <vector>

namespace steady::detail {

struct Quartic {
  std::array<double, 5> c{};

  static Quartic constant(double a) { Quartic p; p.c[0] = a; return p; }
  static Quartic linear(double a0, double a1) { Quartic p; p.c[0] = a0; p.c[1] = a1; return p; }

  double operator()(double x) const { return (((c[4] * x + c[3]) * x + c[2]) * x + c[1]) * x + c[0]; }
  Quartic derivative() const {
    Quartic d;
    for (int k = 1; k < 5; ++k) d.c[k - 1] = k * c[k];
    return d;
  }
  int degree() const {
    for (int k = 4; k > 0; --k)
      if (c[k] != 0.0) return k;
    return 0;
  }
  friend Quartic operator+(Quartic a, const Quartic& b) {
    for (int k = 0; k < 5; ++k) a.c[k] += b.c[k];
    return a;
  }
  friend Quartic operator-(Quartic a, const Quartic& b) {
    for (int k = 0; k < 5; ++k) a.c[k] -= b.c[k];
    return a;
  }
  friend Quartic operator*(double s, Quartic a) {
    for (double& v : a.c) v *= s;
    return a;
  }
  // The product; the caller keeps the total degree within 4.
  friend Quartic operator*(const Quartic& a, const Quartic& b) {
    Quartic p;
    for (int i = 0; i < 5; ++i)
      for (int j = 0; i + j < 5; ++j) p.c[i + j] += a.c[i] * b.c[j];
    return p;
  }
};

inline double bisect_root(const Quartic& p, double lo, double hi) {
  double flo = p(lo);
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    const double fm = p(mid);
    if (fm == 0.0) return mid;
    if ((fm < 0.0) == (flo < 0.0)) {
      lo = mid;
      flo = fm;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

// Real roots of p in (lo, hi) where p changes sign, ascending.
inline std::vector<double> roots_in(const Quartic& p, double lo, double hi) {
  std::vector<double> out;
  const int degree = p.degree();
  if (degree == 0 || !(hi > lo)) return out;
  if (degree == 1) {
    const double x = -p.c[0] / p.c[1];
    if (x > lo && x < hi) out.push_back(x);
    return out;
  }
  std::vector<double> knots{lo};
  for (double x : roots_in(p.derivative(), lo, hi)) knots.push_back(x);
  knots.push_back(hi);
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const double a = knots[k], b = knots[k + 1];
    const double fa = p(a), fb = p(b);
    if (fa == 0.0 && k > 0) out.push_back(a);
    if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0)) out.push_back(bisect_root(p, a, b));
  }
  return out;
}

}  // namespace steady::detail
