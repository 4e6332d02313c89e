#include "lattice/hub_collars.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "lattice/cone_envelope.hpp"
#include "steady/core/errors.hpp"
#include "steady/lattice/convex_distance.hpp"

namespace steady {

namespace {

using hull::kCollarClearance;
constexpr double kTwoPi = 2.0 * M_PI;
// Each collar's angular cone gets this fraction of half the smallest angle to a neighbour's axis.
constexpr double kCollarAngleShare = 0.9;

[[noreturn]] void unsupported(const std::string& why) { fail_input("hub", why); }

using hull::Cone;
Cone make_cone(const CoreStump& st) { return hull::make_cone(st.direction, st.sin_phi); }

// Collars just beyond each stump's envelope in the arrangement of stumps sharing their end radius (scaled to the
// unit sphere, the ball's sphere at exit_v). Empty when another stump dominates some generator again farther out
// (stumps meeting away from the hub: the conservative collars then decide) or a collar would come near the apex.
std::vector<double> envelope_collars(const std::vector<CoreStump>& stumps, double margin) {
  const double rho = shared_end_radius(stumps);
  const std::vector<Cone> cones = envelope_cones(stumps);
  const double exit_v = cones[0].exit_v;
  std::vector<double> collars;
  for (int i = 0; i < static_cast<int>(cones.size()); ++i) {
    std::vector<double> us = hull::breakpoint_candidates(cones, i);
    for (int k = 0; k < hull::kEnvelopeProbes; ++k) us.push_back(kTwoPi * k / hull::kEnvelopeProbes);
    double top = exit_v;
    for (double u : us) {
      if (hull::ceiling_at(cones, i, u) < std::numeric_limits<double>::infinity()) return {};
      top = std::max(top, hull::envelope_at(cones, i, u).v);
    }
    // The margin is twice the clearance the arrangement then checks at its probes: the envelope may peak between them.
    const double v = top + margin;
    const Cone& k = cones[i];
    if (!(k.c - v * k.s > 0.1 * k.c)) return {};
    collars.push_back((k.s + v * k.c) * rho);
  }
  return collars;
}

}  // namespace

std::vector<hull::Cone> envelope_cones(const std::vector<CoreStump>& stumps) {
  const double ball = 1.0 / shared_end_radius(stumps);
  const double exit_v = std::sqrt((ball - 1.0) * (ball + 1.0));
  std::vector<Cone> cones;
  for (const CoreStump& st : stumps) cones.push_back(hull::make_cone(st.direction, st.sin_phi, exit_v));
  return cones;
}

namespace {
// End radii this close above 1 are the hull model's 1 (core_kind calls a beam tangent within 1e-12 as well).
constexpr double kTangentRounding = 1e-12;
}  // namespace

bool share_end_radius(const std::vector<CoreStump>& stumps) {
  if (stumps.empty()) return false;
  for (const CoreStump& s : stumps)
    if (!(std::abs(s.end_radius - stumps[0].end_radius) <= 1e-12 * stumps[0].end_radius)) return false;
  return stumps[0].end_radius > 0.0 && stumps[0].end_radius <= 1.0 + kTangentRounding;
}

double shared_end_radius(const std::vector<CoreStump>& stumps) { return std::min(stumps.at(0).end_radius, 1.0); }

double envelope_clearance(CollarFit fit) {
  return fit == CollarFit::Roomy ? kCollarClearance : 0.5 * kTightCollarMargin;
}

std::vector<double> core_collars(const std::vector<CoreStump>& stumps, CoreKind kind, double max_position,
                                 CollarFit fit) {
  // The hull model is the case rho = 1.
  if (share_end_radius(stumps)) {
    std::vector<double> near = envelope_collars(stumps, 2.0 * envelope_clearance(fit));
    if (!near.empty()) return near;
  }
  return place_collars(stumps, kind, max_position);
}

// How far the ray from the center along unit w stays in stump i: the stump is the beam's cone region between the
// plane where the cone touches its end ball (axial r0 sin_phi) and the collar; the ray meets it in an interval,
// and the far end counts when the interval starts inside the ball (it always does: the cone lies outside the
// ball, so a ray leaving the ball before that plane cannot come back into the cone).
StumpReach::StumpReach(const CoreStump& s, double collar)
    : axis_(glm::normalize(s.direction)),
      sin_phi_(s.sin_phi),
      cos_phi_(std::sqrt((1.0 - s.sin_phi) * (1.0 + s.sin_phi))),
      end_radius_(s.end_radius),
      start_(s.end_radius * s.sin_phi),  // axial position of the end ball's tangent plane
      collar_(collar),
      // k <= 0 gives 0 when start > 0, and 0 < k < start puts the interval's start beyond the ball
      quick_zero_(start_ > 0.0 ? start_ * (1.0 - 1e-9) : -std::numeric_limits<double>::infinity()),
      // On the unit sphere the cone's region is where c sqrt(1 - k^2) + k s - r0 <= 0: concave in k, above 0 at the
      // tangent plane for r0 < 1 (0 there in the hull model, r0 = 1) and below at the axis, so it is
      // k >= cos(asin(r0) - phi), the exit circle (the tangent circle in the hull model).
      exit_k_(std::cos(std::asin(std::min(end_radius_, 1.0)) - std::asin(sin_phi_)) - 1e-9) {}

double StumpReach::reach(double k) const {
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();
  // axial = rho k >= start
  if (k > 0.0) lo = std::max(lo, start_ / k);
  else if (k < 0.0) hi = std::min(hi, start_ / k);
  else if (start_ > 0.0) return 0.0;
  // axial <= collar
  if (k > 0.0) hi = std::min(hi, collar_ / k);
  // radial <= radius(axial): rho (c sqrt(1 - k^2) + k sin_phi) <= r0
  const double denom = cos_phi_ * std::sqrt(std::max(0.0, 1.0 - k * k)) + k * sin_phi_;
  if (denom > 0.0) hi = std::min(hi, end_radius_ / denom);
  else if (end_radius_ < 0.0) return 0.0;
  if (!(hi >= lo) || lo > 1.0) return 0.0;
  return hi;
}

double stump_reach(const CoreStump& s, double collar, const Vec3& w) { return StumpReach(s, collar)(w); }


// A crowded hub's stumps for its core, from its caps (in the hub's canonical frame, or in the world frame scaled
// to the ball: the core's collars depend on angles and distances only) and the slopes and end radii in its
// geometry's extras.
std::vector<CoreStump> core_stumps(const std::vector<SphereCap>& caps, const std::vector<double>& extras) {
  std::vector<CoreStump> stumps;
  for (std::size_t k = 0; k < caps.size(); ++k) {
    CoreStump st;
    st.direction = caps[k].direction;
    st.exit = caps[k].exit;
    st.sin_phi = extras[2 * k];
    st.end_radius = extras[2 * k + 1];
    stumps.push_back(st);
  }
  return stumps;
}

CoreKind core_kind(int hub_kind) { return hub_kind == 1 ? CoreKind::Hull : CoreKind::Transversal; }

std::vector<CoreStump> core_stumps(const Hub& hub) {
  const double R = hub.ball.radius;
  std::vector<CoreStump> stumps;
  for (const Stump& s : hub.stumps) {
    CoreStump st;
    st.direction = s.cone.axis;
    st.exit = s.exit_position / R;
    st.sin_phi = s.cone.sin_phi;  // the cone is oriented from the hub's node
    st.end_radius = s.cone.ra / R;
    stumps.push_back(st);
  }
  return stumps;
}

CoreKind core_kind(const Hub& hub) {
  bool all_tangent = true, all_transversal = true;
  for (const Stump& s : hub.stumps) {
    all_tangent = all_tangent && s.cone.ra >= hub.ball.radius * (1.0 - 1e-12);
    all_transversal = all_transversal && s.cone.ra < hub.ball.radius * (1.0 - 1e-9);
  }
  if (!all_tangent && !all_transversal)
    fail_input("hub", "the hub mixes beams tangent to its ball (hull model) with thinner beams");
  return all_tangent ? CoreKind::Hull : CoreKind::Transversal;
}

double cut_between_collars(double from, double to, double cut) {
  const double margin = 0.1 * (to - from);
  if (!(from < to) || (cut > from + margin && cut < to - margin)) return cut;
  return 0.5 * (from + to);
}

double CoreStump::radius_at(double x) const {
  const double c = std::sqrt((1.0 - sin_phi) * (1.0 + sin_phi));
  return (end_radius - x * sin_phi) / c;
}

std::vector<double> place_collars(const std::vector<CoreStump>& stumps, CoreKind kind, double max_position) {
  const int n = static_cast<int>(stumps.size());
  std::vector<double> collar(n);
  // Angular radius of the collar circle seen from the center decreases with its position: give each stump half of
  // its smallest angle to a neighbour (less a margin), then push collars out until they clear the other stumps.
  for (int i = 0; i < n; ++i) {
    double min_angle = M_PI;
    for (int j = 0; j < n; ++j)
      if (j != i)
        min_angle = std::min(min_angle, std::acos(std::clamp(glm::dot(glm::normalize(stumps[i].direction),
                                                                     glm::normalize(stumps[j].direction)), -1.0, 1.0)));
    const double target = 0.5 * min_angle * kCollarAngleShare;
    if (target <= 0.0) unsupported("two stumps leave the ball in the same direction");
    // A narrowing stump must keep a radius: stay well short of its cone's apex.
    double reach = max_position;
    if (stumps[i].sin_phi > 0.0) reach = std::min(reach, 0.9 * stumps[i].end_radius / stumps[i].sin_phi);
    double lo = std::max(stumps[i].exit, 1e-6), hi = reach;
    auto angle = [&](double x) { return std::atan2(stumps[i].radius_at(x), x); };
    if (angle(hi) > target) unsupported("the stumps stay too close to each other to place their collars");
    // A stump whose exit circle already lies inside its share needs no push: its collar starts at the exit.
    if (angle(lo) <= target) hi = lo;
    for (int it = 0; it < 80 && angle(lo) > target; ++it) {
      const double mid = 0.5 * (lo + hi);
      (angle(mid) > target ? lo : hi) = mid;
    }
    // Beyond the ball too: a collar disk never cuts into the ball (for the Boolean cores, it stays untouched).
    collar[i] = std::max({hi, stumps[i].exit + kCollarClearance, 1.0 + kCollarClearance});
  }
  // Clearance of each collar disk from the other stumps' parts before their collars (GJK on the disk and the
  // frustum), and on the hull model the collar circle where its own stump dominates (a linear function on a
  // circle peaks at its center plus its amplitude). Collars grow until all hold; growing one may need another
  // to grow, so repeat until nothing changes.
  std::vector<Cone> cones;
  if (kind == CoreKind::Hull)
    for (const CoreStump& s : stumps) cones.push_back(make_cone(s));
  auto disk = [&](int i, double x) {
    const Vec3 d = glm::normalize(stumps[i].direction);
    return Circle{x * d, d, stumps[i].radius_at(x)};
  };
  auto clear_of = [&](int i, int j) {
    const Vec3 d = glm::normalize(stumps[i].direction);
    if (kind == CoreKind::Hull) {
      const Cone& kj = cones[j];
      const Vec3 center = collar[i] * d;
      const Vec3 g = kj.d / kj.c - d / cones[i].c;
      const double at_center = kj.w(center) - cones[i].w(center);
      const double amplitude = stumps[i].radius_at(collar[i]) * glm::length(g - glm::dot(g, d) * d);
      if (!(at_center + amplitude < -kCollarClearance)) return false;
    }
    const Circle mine = disk(i, collar[i]);
    const Circle j0 = disk(j, stumps[j].end_radius * stumps[j].sin_phi), j1 = disk(j, collar[j]);
    const DistanceBounds dist = convex_distance([&](const Vec3& v) { return disk_support(mine, v); },
                                                [&](const Vec3& v) { return disk_hull_support(j0, j1, v); },
                                                kCollarClearance, kCollarClearance);
    return dist.lower > kCollarClearance;
  };
  for (int round = 0;; ++round) {
    bool grew = false;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        if (j == i) continue;
        while (!clear_of(i, j)) {
          collar[i] *= 1.1;
          grew = true;
          if (collar[i] > max_position || stumps[i].radius_at(collar[i]) <= 0.1 * stumps[i].end_radius)
            unsupported("a stump's collar cannot clear its neighbours before its cut");
        }
      }
    if (!grew) break;
    if (round > 50) unsupported("the collars of a crowded hub do not settle");
  }
  return collar;
}

double core_volume_by_quadrature(const std::vector<CoreStump>& stumps, const std::vector<double>& collars,
                                 int resolution) {
  // Gauss-Legendre in cos(theta) on [-1, 1] (nodes by Newton on the Legendre polynomial), uniform in phi.
  const int m = resolution;
  std::vector<double> nodes(m), weights(m);
  for (int i = 0; i < m; ++i) {
    double x = std::cos(M_PI * (i + 0.75) / (m + 0.5));
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= m; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double dp = m * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) {
        nodes[i] = x;
        weights[i] = 2.0 / ((1.0 - x * x) * dp * dp);
        break;
      }
    }
  }
  const int nphi = 2 * m;
  double volume = 0.0;
  for (int i = 0; i < m; ++i) {
    const double z = nodes[i], r = std::sqrt(std::max(0.0, 1.0 - z * z));
    for (int k = 0; k < nphi; ++k) {
      const double phi = kTwoPi * (k + 0.5) / nphi;
      const Vec3 w(r * std::cos(phi), r * std::sin(phi), z);
      double reach = 1.0;
      for (std::size_t s = 0; s < stumps.size(); ++s) reach = std::max(reach, stump_reach(stumps[s], collars[s], w));
      volume += weights[i] * (kTwoPi / nphi) * reach * reach * reach / 3.0;
    }
  }
  return volume;
}

}  // namespace steady
