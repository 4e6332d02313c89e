#pragma once
// Numerical references for the COTS / BeCOTS tests, independent of the closed forms under test: Gauss-Legendre
// quadrature, derivatives by a five-point stencil, a line that prints a measured figure, and the text of a refusal.
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "steady/core/errors.hpp"

namespace cots_test {

// The message of the InvalidInput that f throws, or "(no error)".
template <class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const steady::InvalidInput& e) {
    return e.what();
  }
  return "(no error)";
}

constexpr double kPi = 3.14159265358979323846;

// Nodes and weights of n-point Gauss-Legendre quadrature on [0, 1] (Newton on the Legendre polynomial).
inline void gauss_legendre(int n, std::vector<double>* nodes, std::vector<double>* weights) {
  nodes->assign(n, 0.0);
  weights->assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1, p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / dp;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    (*nodes)[i] = 0.5 * (1.0 - x);
    (*weights)[i] = 1.0 / ((1.0 - x * x) * dp * dp);  // 2/((1-x^2) p'^2), halved for [0, 1]
  }
}

// The integral over [0,1]^2 of f(x, y) by an n x n Gauss-Legendre rule, each axis split into `pieces` panels.
inline double integrate_square(const std::function<double(double, double)>& f, int n = 20, int pieces = 4) {
  std::vector<double> x, w;
  gauss_legendre(n, &x, &w);
  double sum = 0.0;
  const double h = 1.0 / pieces;
  for (int pi = 0; pi < pieces; ++pi)
    for (int pj = 0; pj < pieces; ++pj)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) sum += w[i] * w[j] * h * h * f((pi + x[i]) * h, (pj + x[j]) * h);
  return sum;
}

// d/dt g(t) by the five-point stencil (error h^4 g^(5) / 30).
template <class V, class G>
V derivative(const G& g, double t, double h) {
  return (g(t - 2 * h) - 8.0 * g(t - h) + 8.0 * g(t + h) - g(t + 2 * h)) / (12.0 * h);
}

inline void report(const char* what, double value) { std::printf("[ measured ] %s: %.3g\n", what, value); }

}  // namespace cots_test
