#include "properties/caps_past_cuts.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <vector>

#include "properties/gauss_kronrod.hpp"
#include "properties/quadratic_roots.hpp"
#include "steady/core/constants.hpp"
#include "steady/lattice/convex_distance.hpp"
#include "steady/properties/hub_properties.hpp"

namespace steady {

namespace {

// The ball x.x <= R^2 beyond the plane x.n >= d (0 < d < R), about the ball's center: by slices z along n of
// radius^2 R^2 - z^2; its surface is the sphere's zone 2 pi R (R - d) (the base disk lies on the cut plane).
MassMoments cap_moments(double R, double d, const Vec3& n) {
  const double R2 = R * R;
  auto between = [&](auto antiderivative) { return antiderivative(R) - antiderivative(d); };
  const double volume = kPi * between([&](double z) { return R2 * z - z * z * z / 3.0; });
  const double axial_first = kPi * between([&](double z) { return R2 * z * z / 2.0 - z * z * z * z / 4.0; });
  const double axial_second = kPi * between([&](double z) { return R2 * z * z * z / 3.0 - std::pow(z, 5) / 5.0; });
  // Each slice's integral of rho^2 is pi a^4 / 2 with a^2 = R^2 - z^2.
  const double radial_second =
      0.5 * kPi * between([&](double z) { return R2 * R2 * z - 2.0 * R2 * z * z * z / 3.0 + std::pow(z, 5) / 5.0; });
  return axisymmetric_moments(n, volume, axial_first, axial_second, radial_second, 2.0 * kPi * R * (R - d));
}

// The support map (convex_distance.hpp) of the cap beyond the plane x.n >= d of the ball (center c, radius R): the
// hull of its spherical zone and base disk.
Vec3 cap_support(const Vec3& c, double R, const Vec3& n, double d, const Vec3& direction) {
  const double length = glm::length(direction);
  const Vec3 u = length > 0.0 ? direction / length : n;
  if (R * glm::dot(u, n) >= d) return c + R * u;
  return disk_support(Circle{c + d * n, n, std::sqrt(R * R - d * d)}, u);
}

// Along a meridian of the cap (polar angle theta from its axis n, in the half-plane of unit w across it), the
// cap's radial integrals from the cut plane (r = d / cos theta) to the sphere (r = R), integrated over theta:
// antiderivatives in c = cos theta, s = sin theta. Components: volume; first moment along n and along w; second
// moment n n, n w (each of the two cross terms), w w; the sphere's area.
enum CapComponent { kCapVolume, kCapFirstN, kCapFirstW, kCapSecondNN, kCapSecondNW, kCapSecondWW, kCapArea, kCapCount };
using CapIntegrals = std::array<double, kCapCount>;

CapIntegrals meridian_antiderivative(double R, double d, double theta) {
  const double c = std::cos(theta), s = std::sin(theta), t = std::tan(theta);
  const double R3 = R * R * R, R4 = R3 * R, R5 = R4 * R, d3 = d * d * d, d4 = d3 * d, d5 = d4 * d;
  CapIntegrals a;
  a[kCapVolume] = -(R3 * c + 0.5 * d3 / (c * c)) / 3.0;
  a[kCapFirstN] = -(R4 * c * c + d4 / (c * c)) / 8.0;
  a[kCapFirstW] = (R4 * 0.5 * (theta - s * c) - d4 * t * t * t / 3.0) / 4.0;
  a[kCapSecondNN] = (-R5 * c * c * c / 3.0 - 0.5 * d5 / (c * c)) / 5.0;
  a[kCapSecondNW] = (R5 * s * s * s - d5 * t * t * t) / 15.0;
  a[kCapSecondWW] = (R5 * (c * c * c / 3.0 - c) - d5 * (0.25 / (c * c * c * c) - 0.5 / (c * c))) / 5.0;
  a[kCapArea] = -R * R * c;
  return a;
}

// Where the cut disk's radius p(tau) = d n + tau w (0 <= tau <= tau_max, w unit across n; the ball at the origin)
// lies in stump k's frustum { touch <= x <= cut, |p|^2 - x^2 <= r(x)^2, r(x) >= 0 } with x = p . axis: the frustum
// is convex, so one interval, [lo, hi], or none.
bool span_in_frustum(const Stump& k, const Vec3& n, const Vec3& w, double d, double tau_max, double& lo, double& hi) {
  const BeamCone& cone = k.cone;
  const double x0 = d * glm::dot(n, cone.axis), dx = glm::dot(w, cone.axis);
  const double s = cone.sin_phi, c2 = cone.cos_phi * cone.cos_phi, h0 = cone.ra - x0 * s;
  std::vector<double> breaks{0.0, tau_max};
  for (double plane : {cone.ra * s, k.cut_position, s != 0.0 ? cone.ra / s : std::nan("")})
    if (dx != 0.0 && std::isfinite(plane)) breaks.push_back((plane - x0) / dx);
  std::vector<double> roots;
  quadratic_roots(c2 * (1.0 - dx * dx) - dx * dx * s * s, -c2 * x0 * dx + h0 * dx * s, c2 * (d * d - x0 * x0) - h0 * h0,
                  roots);
  breaks.insert(breaks.end(), roots.begin(), roots.end());
  std::sort(breaks.begin(), breaks.end());
  bool found = false;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double a = std::max(0.0, breaks[i]), b = std::min(tau_max, breaks[i + 1]);
    if (!(b > a)) continue;
    const double tau = 0.5 * (a + b), x = x0 + tau * dx, r = (cone.ra - x * s) / cone.cos_phi;
    if (!(x >= cone.ra * s && x <= k.cut_position && r >= 0.0 && d * d + tau * tau - x * x <= r * r)) continue;
    lo = found ? std::min(lo, a) : a;
    hi = found ? std::max(hi, b) : b;
    found = true;
  }
  return found;
}

// The part of the cap (beyond the plane x.n >= d of the ball of radius R at the origin) that hub_properties keeps
// in its hub: along each meridian of the cap (the half-plane of w at angle psi), the directions in which the cut
// disk lies inside a neighbouring stump's frustum (hidden there, the disk takes nothing from the ball). Adaptive
// quadrature over psi of the closed-form integrals over theta.
MassMoments cap_part_kept(double R, double d, const Vec3& n, const std::vector<const Stump*>& neighbours) {
  const Vec3 e1 = glm::normalize(std::abs(n.x) < 0.9 ? glm::cross(n, Vec3(1, 0, 0)) : glm::cross(n, Vec3(0, 1, 0)));
  const Vec3 e2 = glm::cross(n, e1);
  const double tau_max = std::sqrt(R * R - d * d);
  constexpr std::size_t kN = 11;  // volume, first (3), second (6), area
  auto f = [&](double psi) {
    detail::Sample<kN> sample;
    const Vec3 w = std::cos(psi) * e1 + std::sin(psi) * e2;
    std::vector<std::pair<double, double>> spans;
    std::uint64_t signature = 1469598103934665603ull;
    for (std::size_t k = 0; k < neighbours.size(); ++k) {
      double lo = 0.0, hi = 0.0;
      if (!span_in_frustum(*neighbours[k], n, w, d, tau_max, lo, hi)) continue;
      spans.emplace_back(std::atan2(lo, d), std::atan2(hi, d));
      signature = (signature ^ (4 * k + (lo == 0.0 ? 1 : 0) + (hi == tau_max ? 2 : 0) + 64)) * 1099511628211ull;
    }
    std::sort(spans.begin(), spans.end());
    CapIntegrals sum{};
    double until = 0.0;
    for (const auto& [lo, hi] : spans) {
      const double from = std::max(lo, until);
      if (hi > from) {
        const CapIntegrals A = meridian_antiderivative(R, d, hi), B = meridian_antiderivative(R, d, from);
        for (int c = 0; c < kCapCount; ++c) sum[c] += A[c] - B[c];
      }
      until = std::max(until, hi);
    }
    const Mat3 nn = glm::outerProduct(n, n), nw = glm::outerProduct(n, w) + glm::outerProduct(w, n);
    const Mat3 ww = glm::outerProduct(w, w);
    const Vec3 first = sum[kCapFirstN] * n + sum[kCapFirstW] * w;
    const Mat3 second = sum[kCapSecondNN] * nn + sum[kCapSecondNW] * nw + sum[kCapSecondWW] * ww;
    sample.value = {sum[kCapVolume], first.x,      first.y,      first.z,      second[0][0], second[0][1],
                    second[0][2],    second[1][1], second[1][2], second[2][2], sum[kCapArea]};
    sample.signature = signature;
    return sample;
  };
  const MassMoments whole = cap_moments(R, d, n);
  std::array<double, kN> scale;
  scale.fill(whole.volume * R * R);
  scale[0] = whole.volume;
  scale[1] = scale[2] = scale[3] = whole.volume * R;
  scale[10] = whole.area;
  const std::array<double, kN> v = detail::integrate_adaptive<kN>(f, 0.0, 2.0 * kPi, {}, scale, 1e-12, 1e-9).value;
  MassMoments m;
  m.volume = v[0];
  m.first = Vec3(v[1], v[2], v[3]);
  m.second = Mat3(v[4], v[5], v[6], v[5], v[7], v[8], v[6], v[8], v[9]);
  m.area = v[10];
  return m;
}

}  // namespace

MassMoments caps_past_cuts(const Hub& h, std::string& refusal) {
  const double R = h.ball.radius;
  std::vector<std::size_t> capped;  // the stumps whose cut plane crosses the ball
  MassMoments out;
  for (std::size_t k = 0; k < h.stumps.size(); ++k) {
    const Stump& s = h.stumps[k];
    const double d = s.cut_position;
    if (!(d < R)) continue;
    if (!(d > 0.0)) {
      refusal = "a cut plane passes through or behind its ball's center";
      return out;
    }
    capped.push_back(k);
    out += cap_moments(R, d, s.cone.axis);
  }
  // Whether two bodies meet, by their distance (both shrunk by 1e-9 of the ball: bodies that only touch do not).
  const double shrink = 1e-9 * R;
  auto shrunk = [&](const Vec3& p, const Vec3& u) {
    const double length = glm::length(u);
    return length > 0.0 ? p - shrink * u / length : p;
  };
  auto meet = [&](const SupportMap& a, const SupportMap& b) {
    const DistanceBounds gap = convex_distance([&](const Vec3& u) { return shrunk(a(u), u); },
                                               [&](const Vec3& u) { return shrunk(b(u), u); }, 0.0, 1e-12 * R);
    return gap.intersecting || !(gap.lower > 0.0);
  };
  auto cap_of = [&](std::size_t k) -> SupportMap {
    const Stump& s = h.stumps[k];
    return [&h, &s, R](const Vec3& u) { return cap_support(h.ball.center, R, s.cone.axis, s.cut_position, u); };
  };
  for (std::size_t a = 0; a < capped.size(); ++a)
    for (std::size_t b = a + 1; b < capped.size(); ++b)
      if (meet(cap_of(capped[a]), cap_of(capped[b]))) refusal = "the caps of its ball beyond two beams' cuts meet";
  // hub_properties integrates a stump's cap alone (the whole cap beyond the cut goes) unless other stumps' exit
  // caps overlap it; then, along each meridian, the stretches of its cut disk inside those stumps are hidden and
  // take nothing from the ball: the cap's part there stays in the hub, and is no difference from the Fuse's.
  const HubShape shape = hub_shape(h);
  for (std::size_t j : capped) {
    std::vector<const Stump*> neighbours;
    for (std::size_t k = 0; k < h.stumps.size(); ++k)
      if (k != j && stump_caps_overlap(R, shape.stumps[j], shape.stumps[k])) neighbours.push_back(&h.stumps[k]);
    const Stump& own = h.stumps[j];
    if (!neighbours.empty()) out -= cap_part_kept(R, own.cut_position, own.cone.axis, neighbours);
  }
  return out;
}

}  // namespace steady
