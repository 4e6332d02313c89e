#include "steady/cots/becots_range.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "cots/cots_math.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/numeric_range.hpp"

namespace steady {
namespace {
using cots_detail::Complex;
using cots_detail::kTwoPi;

constexpr double kPi = 0.5 * kTwoPi;

// Widening of every bound (log-distance, radians, parameters) so that rounding never drops a group: the
// coordinates are computed to ~1e-15, and a group more is harmless (the exact test follows).
constexpr double kRangePad = 1e-9;

// floor / ceil of a double clamped into [lo, hi] before the conversion (the bounds may be huge or infinite).
int clamped_floor(double v, int lo, int hi) { return static_cast<int>(std::clamp(std::floor(v), double(lo), double(hi))); }
int clamped_ceil(double v, int lo, int hi) { return static_cast<int>(std::clamp(std::ceil(v), double(lo), double(hi))); }

bool meets(const Ball& a, const Ball& b) { return glm::length(a.center - b.center) <= a.radius + b.radius; }
}  // namespace

BecotsRangeFinder::BecotsRangeFinder(const BecotsMap& map, std::vector<Ball> balls, int nu, int nv, double du,
                                     double dv)
    : map_(map), balls_(std::move(balls)), nu_(nu), nv_(nv), du_(du), dv_(dv) {
  if (nu < 1) fail_input("nu", "must be >= 1 (got " + std::to_string(nu) + ")");
  if (nv < 1) fail_input("nv", "must be >= 1 (got " + std::to_string(nv) + ")");
  require_positive(du, "du");
  require_positive(dv, "dv");
  if (balls_.empty()) fail_input("balls", "the template needs at least one ball");
  const std::optional<Vec3> apex = map.apex();
  if (!apex)
    fail_input("map", "a parallelogram's pattern is a translation lattice (no apex): use the steady-brick layout");
  apex_ = *apex;
  for (std::size_t n = 0; n < balls_.size(); ++n) {
    const std::string name = "balls[" + std::to_string(n) + "]";
    require_within(balls_[n].center, kMaxCoordinate, name + ".center");
    require_finite(balls_[n].radius, name + ".radius");
    if (balls_[n].radius < 0.0) fail_input(name + ".radius", "must be >= 0");
    Bound b = bound_of(balls_[n]);
    // Azimuths on the branch nearest the first ball's: balls on both sides of the cut at +-pi would otherwise
    // bound the template by the long way round between them, and miss the short way they really span.
    if (n > 0 && !b.everything && !template_.everything) {
      const double shift = kTwoPi * std::round((0.5 * (template_.t0 + template_.t1) - 0.5 * (b.t0 + b.t1)) / kTwoPi);
      b.t0 += shift, b.t1 += shift;
    }
    if (n == 0) template_ = b;
    template_.s0 = std::min(template_.s0, b.s0), template_.s1 = std::max(template_.s1, b.s1);
    template_.t0 = std::min(template_.t0, b.t0), template_.t1 = std::max(template_.t1, b.t1);
    template_.p0 = std::min(template_.p0, b.p0), template_.p1 = std::max(template_.p1, b.p1);
    template_.everything = template_.everything || b.everything;
  }
  if (!template_.everything) parameter_box(template_.s0, template_.s1, template_.t0, template_.t1, &tx0_, &tx1_, &ty0_, &ty1_);
}

BecotsRangeFinder::Bound BecotsRangeFinder::bound_of(const Ball& b) const {
  Bound out{0, 0, 0, 0, 0, kPi, true};
  // |c - F|^2 / |A - F|^2 = 1 + t / |A - F|, t = 2 e.n + |e|^2 / |A - F|, e = c - A: the apex is never formed.
  const Vec3 e = b.center - map_.a_;
  const double kappa = map_.inv_length_;
  const double t = 2.0 * glm::dot(e, map_.radial_dir_) + kappa * glm::dot(e, e);
  if (!(1.0 + kappa * t > 0.0)) return out;  // the centre is the apex
  const double log_distance = 0.5 * std::log1p(kappa * t);
  const double distance = std::sqrt(1.0 + kappa * t) / kappa;
  if (!(b.radius < distance)) return out;  // the ball holds the apex
  out.everything = false;
  out.s0 = log_distance + std::log1p(-b.radius / distance) - kRangePad;
  out.s1 = log_distance + std::log1p(b.radius / distance) + kRangePad;
  // Azimuth about the axis from A's, and the distance to the axis, from the shadows on the plane across it.
  const Complex z = map_.shadow_ratio(b.center);
  const double to_axis = std::abs(z) * std::abs(map_.radial_);
  const double azimuth = z == 0.0 ? 0.0 : std::arg(z);
  const double half = b.radius < to_axis ? std::asin(b.radius / to_axis) : kPi;
  out.t0 = azimuth - half - kRangePad;
  out.t1 = azimuth + half + kRangePad;
  // The angle to the axis seen from the apex: invariant under the field.
  const double axial = glm::dot(e, map_.axis_) + map_.height_;
  const double polar = std::atan2(to_axis, axial), spread = std::asin(std::min(1.0, b.radius / distance));
  out.p0 = polar - spread - kRangePad;
  out.p1 = polar + spread + kRangePad;
  return out;
}

BecotsRangeFinder::PolarInterval BecotsRangeFinder::polar_interval(const Ball& b) const {
  const Bound q = bound_of(b);
  return {q.p0, q.p1, q.everything};
}

Vec2 BecotsRangeFinder::parameters_at(double s, double theta) const {
  // The map's scaled system: x pu + y pv = s |A - F|, x qu + y qv = theta |a' - f'|.
  const double along = s / map_.inv_length_, arc = theta * std::abs(map_.radial_);
  const double det = map_.pu_ * map_.qv_ - map_.pv_ * map_.qu_;
  return {(along * map_.qv_ - map_.pv_ * arc) / det, (map_.pu_ * arc - map_.qu_ * along) / det};
}

void BecotsRangeFinder::parameter_box(double s0, double s1, double t0, double t1, double* x0, double* x1, double* y0,
                                      double* y1) const {
  const Vec2 corners[4] = {parameters_at(s0, t0), parameters_at(s1, t0), parameters_at(s0, t1), parameters_at(s1, t1)};
  *x0 = *x1 = corners[0].x;
  *y0 = *y1 = corners[0].y;
  for (const Vec2& c : corners) {
    *x0 = std::min(*x0, c.x), *x1 = std::max(*x1, c.x);
    *y0 = std::min(*y0, c.y), *y1 = std::max(*y1, c.y);
  }
}

std::vector<GroupRange> BecotsRangeFinder::candidates(const Ball& query) const {
  require_within(query.center, kMaxCoordinate, "query.center");
  require_finite(query.radius, "query.radius");
  if (query.radius < 0.0) fail_input("query.radius", "must be >= 0");
  const GroupRange all{0, nu_ - 1, 0, nv_ - 1};
  const Bound q = bound_of(query);
  if (template_.everything || q.everything) return {all};
  if (q.p1 < template_.p0 || q.p0 > template_.p1) return {};  // misses the shell of cones
  // The turns k of the query's azimuth that can meet a group's: the groups' azimuths span the template's plus the
  // field's angles over the index box.
  const double wu = map_.log_u().imag() * du_, wv = map_.log_v().imag() * dv_;
  const double turns[4] = {0.0, (nu_ - 1) * wu, (nv_ - 1) * wv, (nu_ - 1) * wu + (nv_ - 1) * wv};
  const double lo = template_.t0 + *std::min_element(turns, turns + 4);
  const double hi = template_.t1 + *std::max_element(turns, turns + 4);
  const long k0 = static_cast<long>(std::ceil((lo - q.t1) / kTwoPi)), k1 = static_cast<long>(std::floor((hi - q.t0) / kTwoPi));
  std::vector<GroupRange> ranges;
  for (long k = k0; k <= k1; ++k) {
    double x0, x1, y0, y1;
    parameter_box(q.s0, q.s1, q.t0 + kTwoPi * k, q.t1 + kTwoPi * k, &x0, &x1, &y0, &y1);
    // group (i, j) spans the template's box shifted by (i du, j dv)
    GroupRange r{clamped_ceil((x0 - tx1_) / du_ - kRangePad, 0, nu_), clamped_floor((x1 - tx0_) / du_ + kRangePad, -1, nu_ - 1),
                 clamped_ceil((y0 - ty1_) / dv_ - kRangePad, 0, nv_), clamped_floor((y1 - ty0_) / dv_ + kRangePad, -1, nv_ - 1)};
    if (!r.empty()) ranges.push_back(r);
  }
  return ranges;
}

Ball BecotsRangeFinder::ball(int i, int j, int n) const {
  if (i < 0 || i >= nu_) fail_input("i", "must be in 0.." + std::to_string(nu_ - 1) + " (got " + std::to_string(i) + ")");
  if (j < 0 || j >= nv_) fail_input("j", "must be in 0.." + std::to_string(nv_ - 1) + " (got " + std::to_string(j) + ")");
  if (n < 0 || n >= static_cast<int>(balls_.size()))
    fail_input("n", "must be in 0.." + std::to_string(balls_.size() - 1) + " (got " + std::to_string(n) + ")");
  return map_.field(i * du_, j * dv_).apply(balls_[n]);
}

std::vector<PatternBall> BecotsRangeFinder::interfering(const Ball& query) const {
  std::vector<PatternBall> found;
  for (const GroupRange& r : candidates(query))
    for (int j = r.j0; j <= r.j1; ++j)
      for (int i = r.i0; i <= r.i1; ++i) {
        const Similarity s = map_.field(i * du_, j * dv_);
        for (int n = 0; n < static_cast<int>(balls_.size()); ++n)
          if (meets(s.apply(balls_[n]), query)) found.push_back({i, j, n});
      }
  // Ranges of different turns may share groups when the pattern overlaps itself: report each ball once.
  std::sort(found.begin(), found.end(), [](const PatternBall& a, const PatternBall& b) {
    return std::tie(a.j, a.i, a.n) < std::tie(b.j, b.i, b.n);
  });
  found.erase(std::unique(found.begin(), found.end(),
                          [](const PatternBall& a, const PatternBall& b) { return a.i == b.i && a.j == b.j && a.n == b.n; }),
              found.end());
  return found;
}

std::vector<PatternBall> BecotsRangeFinder::interfering_naive(const Ball& query) const {
  std::vector<PatternBall> found;
  for (int j = 0; j < nv_; ++j)
    for (int i = 0; i < nu_; ++i) {
      const Similarity s = map_.field(i * du_, j * dv_);
      for (int n = 0; n < static_cast<int>(balls_.size()); ++n)
        if (meets(s.apply(balls_[n]), query)) found.push_back({i, j, n});
    }
  return found;
}

}  // namespace steady
