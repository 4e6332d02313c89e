#include "steady/cots/becots_sums.hpp"

#include <cmath>
#include <optional>
#include <string>

#include "cots/cots_math.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/numeric_range.hpp"

namespace steady {
namespace {
using cots_detail::Complex;

constexpr double kPi = 3.14159265358979323846;

// sum_{k < n} e^{k L} = n phi(n L) / phi(L), phi(z) = (e^z - 1)/z: no cancellation as L -> 0 (then n).
Complex geometric(Complex L, int n) {
  const Complex p = cots_detail::phi(L);
  if (p == 0.0) return static_cast<double>(n);  // L a whole number of turns: every term is 1
  return static_cast<double>(n) * cots_detail::phi(static_cast<double>(n) * L) / p;
}

void require_pattern(int nu, int nv, double du, double dv) {
  if (nu < 1) fail_input("nu", "must be >= 1 (got " + std::to_string(nu) + ")");
  if (nv < 1) fail_input("nv", "must be >= 1 (got " + std::to_string(nv) + ")");
  require_positive(du, "du");
  require_positive(dv, "dv");
}
}  // namespace

double becots_scale_sum(const BecotsMap& map, double power, int nu, int nv, double du, double dv) {
  require_pattern(nu, nv, du, dv);
  require_finite(power, "power");
  return geometric(power * du * map.log_u().real(), nu).real() * geometric(power * dv * map.log_v().real(), nv).real();
}

PatternProperties becots_ball_pattern_properties(const BecotsMap& map, const std::vector<Ball>& balls, int nu, int nv,
                                                 double du, double dv) {
  require_pattern(nu, nv, du, dv);
  const Complex lu = map.log_u(), lv = map.log_v();
  const double volume_sum = becots_scale_sum(map, 3.0, nu, nv, du, dv);
  const double area_sum = becots_scale_sum(map, 2.0, nu, nv, du, dv);
  const std::optional<Vec3> apex = map.apex();
  PatternProperties out;
  Vec3 moment(0.0);
  for (std::size_t n = 0; n < balls.size(); ++n) {
    const std::string name = "balls[" + std::to_string(n) + "]";
    require_within(balls[n].center, kMaxCoordinate, name + ".center");
    require_finite(balls[n].radius, name + ".radius");
    if (balls[n].radius < 0.0) fail_input(name + ".radius", "must be >= 0");
    const double r = balls[n].radius;
    const double v = 4.0 / 3.0 * kPi * r * r * r;
    out.volume += v * volume_sum;
    out.area += 4.0 * kPi * r * r * area_sum;
    if (!apex) {
      // Translations only (scale 1): the copies' centres average to c + mean shift.
      const Vec3 shift = 0.5 * (nu - 1) * du * (map.d() - map.a()) + 0.5 * (nv - 1) * dv * (map.b() - map.a());
      moment += v * volume_sum * (balls[n].center + shift);
      continue;
    }
    // c - F = along T + zeta across it (zeta complex in the plane frame); copies: F + s (along T + e^{i theta} zeta).
    const Vec3 cf = balls[n].center - *apex;
    const double along = glm::dot(cf, map.axis());
    const Complex zeta(glm::dot(cf, map.plane_x()), glm::dot(cf, map.plane_y()));
    const double s4 = becots_scale_sum(map, 4.0, nu, nv, du, dv);
    const Complex spin = geometric(du * Complex(4.0 * lu.real(), lu.imag()), nu) *
                         geometric(dv * Complex(4.0 * lv.real(), lv.imag()), nv) * zeta;
    moment += v * (volume_sum * *apex + s4 * along * map.axis() + spin.real() * map.plane_x() + spin.imag() * map.plane_y());
  }
  if (out.volume > 0.0) out.centroid = moment / out.volume;
  return out;
}

}  // namespace steady
