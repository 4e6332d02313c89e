#pragma once
// Adaptive Gauss-Kronrod (7-point Gauss, 15-point Kronrod) quadrature of a vector-valued function, with
// given breakpoints (where the integrand is known to kink) and per-component error scales. The abscissae
// and weights are the standard ones (Kronrod 1965; as tabulated in QUADPACK's qk15).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace steady::detail {

constexpr std::array<double, 8> kKronrodNodes = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851, 0.864864423359769072789712788640926,
    0.741531185599394439863864773280788, 0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
constexpr std::array<double, 8> kKronrodWeights = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204, 0.104790010322250183839876322541518,
    0.140653259715525918745189590510238, 0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
// Gauss weights of the 7-point rule, whose nodes are the Kronrod nodes 1, 3, 5 and 7.
constexpr std::array<double, 4> kGaussWeights = {0.129484966168869693270611432679082,
                                                 0.279705391489276667901467771423780,
                                                 0.381830050505118944950369775488975,
                                                 0.417959183673469387755102040816327};

template <std::size_t N>
struct QuadratureResult {
  std::array<double, N> value{};
  double error = 0.0;   // max over components of |error| / scale
  long evaluations = 0;
};

// A sample of the integrand: its value, and a signature of the integrand's combinatorial structure at that
// point (which formula applies). The integrand is smooth where the signature is constant; the integrator
// splits intervals exactly where it changes (found by bisection), so kinks never hide between nodes.
template <std::size_t N>
struct Sample {
  std::array<double, N> value{};
  std::uint64_t signature = 0;
};

// One Kronrod-Gauss evaluation of f on [lo, hi]: the Kronrod value per component, and the error estimate
// max_c error_c / scale_c with error_c = |K15 - G7|, never below the rounding floor 50 eps * integral of
// |f|. The raw difference is used on purpose: QUADPACK's sharper (200 |K - G| / spread)^1.5 heuristic
// assumes a smooth integrand and underrates kinks by orders of magnitude (seen on hub integrands).
// When the signatures of the nodes and of the two ends are not all equal, `change_lo` < `change_hi`
// bracket a change (consecutive sample positions with different signatures).
template <std::size_t N>
struct KronrodInterval {
  double lo = 0.0, hi = 0.0;
  std::array<double, N> value{};
  double error = 0.0;
  bool at_rounding_floor = false;
  double change_lo = 0.0, change_hi = 0.0;
  bool has_change() const { return change_hi > change_lo; }
  bool operator<(const KronrodInterval& o) const { return error < o.error; }
};

template <std::size_t N, class F>
KronrodInterval<N> kronrod_interval(const F& f, double lo, double hi, const std::array<double, N>& scale) {
  constexpr double kRoundoff = 50.0 * 2.220446049250313e-16;
  KronrodInterval<N> out;
  out.lo = lo;
  out.hi = hi;
  const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  std::array<double, N> kronrod{}, gauss{}, absolute{};
  // positions in increasing order with their signatures: lo, the 15 nodes, hi
  std::array<std::pair<double, std::uint64_t>, 17> marks;
  marks[0] = {lo, f(lo).signature};
  marks[16] = {hi, f(hi).signature};
  for (int n = 0; n < 8; ++n) {
    const double dx = half * kKronrodNodes[n];
    for (int side = 0; side < (n == 7 ? 1 : 2); ++side) {
      const double x = side == 0 ? mid + dx : mid - dx;
      const Sample<N> v = f(x);
      marks[side == 0 ? 15 - n : 1 + n] = {x, v.signature};
      for (std::size_t c = 0; c < N; ++c) {
        kronrod[c] += kKronrodWeights[n] * v.value[c];
        absolute[c] += kKronrodWeights[n] * std::abs(v.value[c]);
        if (n % 2 == 1) gauss[c] += kGaussWeights[n / 2] * v.value[c];
      }
    }
  }
  for (int k = 0; k + 1 < 17; ++k)
    if (marks[k].second != marks[k + 1].second) {
      out.change_lo = marks[k].first;
      out.change_hi = marks[k + 1].first;
      break;
    }
  out.at_rounding_floor = true;
  for (std::size_t c = 0; c < N; ++c) {
    const double raw = half * std::abs(kronrod[c] - gauss[c]);
    out.value[c] = half * kronrod[c];
    double e = raw;
    const double floor = kRoundoff * half * absolute[c];
    if (e > floor) out.at_rounding_floor = false;
    e = std::max(e, floor);
    if (scale[c] > 0.0) out.error = std::max(out.error, e / scale[c]);
  }
  return out;
}

// Integrates f over [a, b] split at `breaks`; f(x) returns Sample<N>. Globally adaptive: intervals whose
// samples change signature are split where it changes; otherwise the interval with the largest error is
// bisected, until the summed error is at most `tolerance` (relative to the scales). Intervals at the
// rounding floor or narrower than min_width are not split further; after max_evaluations the result is
// returned with its error estimate.
// Signature changes are followed only when they lie at least signature_min_width from both ends of their
// interval: a kink closer than d to an end changes the Kronrod value by at most |slope jump| d^2 / 2, and
// where rounding makes the structure flicker near a degenerate point, the error estimate alone decides.
template <std::size_t N, class F>
QuadratureResult<N> integrate_adaptive(const F& f, double a, double b, std::vector<double> breaks,
                                       const std::array<double, N>& scale, double tolerance,
                                       double signature_min_width, double min_width_fraction = 1e-13,
                                       long max_evaluations = 2'000'000) {
  QuadratureResult<N> out;
  const double total = b - a;
  if (!(total > 0.0)) return out;
  breaks.push_back(a);
  breaks.push_back(b);
  std::sort(breaks.begin(), breaks.end());
  const double min_width = min_width_fraction * total;
  const double resolution = signature_min_width;
  std::vector<KronrodInterval<N>> heap, settled;
  double error = 0.0;
  std::vector<std::pair<double, double>> pending;
  auto add = [&](double lo, double hi) {
    KronrodInterval<N> iv = kronrod_interval(f, lo, hi, scale);
    out.evaluations += 17;
    if (iv.has_change() && hi - lo > 2.0 * resolution && out.evaluations < max_evaluations) {
      // Locate the change to the last bit and split there.
      double x0 = iv.change_lo, x1 = iv.change_hi;
      const std::uint64_t s0 = f(x0).signature;
      while (x1 - x0 > min_width) {
        const double xm = 0.5 * (x0 + x1);
        if (xm <= x0 || xm >= x1) break;
        ++out.evaluations;
        (f(xm).signature == s0 ? x0 : x1) = xm;
      }
      const double cut = 0.5 * (x0 + x1);
      if (cut - lo > resolution && hi - cut > resolution) {
        pending.push_back({lo, cut});
        pending.push_back({cut, hi});
        return;
      }
    }
    error += iv.error;
    if (iv.at_rounding_floor || hi - lo <= min_width) {
      settled.push_back(iv);
    } else {
      heap.push_back(iv);
      std::push_heap(heap.begin(), heap.end());
    }
  };
  auto drain = [&]() {
    while (!pending.empty()) {
      const auto [lo, hi] = pending.back();
      pending.pop_back();
      add(lo, hi);
    }
  };
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double lo = std::max(a, breaks[k]), hi = std::min(b, breaks[k + 1]);
    if (hi > lo) pending.push_back({lo, hi});
  }
  drain();
  while (!heap.empty() && error > tolerance && out.evaluations < max_evaluations) {
    std::pop_heap(heap.begin(), heap.end());
    const KronrodInterval<N> worst = heap.back();
    heap.pop_back();
    error -= worst.error;
    const double mid = 0.5 * (worst.lo + worst.hi);
    pending.push_back({worst.lo, mid});
    pending.push_back({mid, worst.hi});
    drain();
  }
  // Sum the values in order of position, for a result independent of the refinement order.
  settled.insert(settled.end(), heap.begin(), heap.end());
  std::sort(settled.begin(), settled.end(), [](const auto& x, const auto& y) { return x.lo < y.lo; });
  for (const auto& iv : settled)
    for (std::size_t c = 0; c < N; ++c) out.value[c] += iv.value[c];
  out.error = std::max(0.0, error);
  return out;
}

}  // namespace steady::detail
