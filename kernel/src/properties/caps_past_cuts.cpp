#include "properties/caps_past_cuts.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

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
  // hub_properties sees a hub from its center: in the directions through a cap it ends at the cut plane, unless
  // another stump's cone leaves the ball there (its exit cap). So each cap's directions, within acos(d / R) of its
  // axis, must keep clear of every other stump's exit cap.
  const HubShape shape = hub_shape(h);
  for (std::size_t a = 0; a < capped.size(); ++a) {
    for (std::size_t b = a + 1; b < capped.size(); ++b)
      if (meet(cap_of(capped[a]), cap_of(capped[b]))) refusal = "the caps of its ball beyond two beams' cuts meet";
    const Stump& own = h.stumps[capped[a]];
    const double spread = std::acos(std::clamp(own.cut_position / R, -1.0, 1.0));
    for (std::size_t k = 0; k < h.stumps.size(); ++k) {
      if (k == capped[a] || !h.stumps[k].cone.has_lateral_surface()) continue;
      const double apart = std::acos(std::clamp(glm::dot(own.cone.axis, h.stumps[k].cone.axis), -1.0, 1.0));
      if (!(apart > spread + stump_cap(R, shape.stumps[k]).half_angle + 1e-9))
        refusal = "the cap of its ball beyond a beam's cut lies in the directions of another beam's stump";
    }
  }
  return out;
}

}  // namespace steady
