#include "steady/properties/hub_properties.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "properties/gauss_kronrod.hpp"
#include "properties/small_polynomial.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/constants.hpp"

namespace steady {
namespace {


// Caps closer than this to touching (radians) are treated as disjoint: the volume two caps overlapping by
// an angle d share outside the ball is O(d^2.5 R^3), below 1e-22 R^3 here.
constexpr double kCapOverlapMargin = 1e-9;

// Kinks of the meridian integrand (where two neighbours' hidden stretches meet) are located and split at
// when they lie at least this far (in the graded variable, 1 per piece between events) from an interval's
// ends; one closer changes the result by at most |slope jump| 1e-12 / 2 of the piece's scale.
constexpr double kKinkResolution = 1e-6;

// The finest tolerance one cap's quadrature is asked for. A cap's integral sums thousands of interval values,
// each rounded at ~1e-16 relative; asking much below 1e-14 makes the refinement chase its own rounding
// (seen: 1e-15 exhausts the evaluation budget and ends further from the truth than 1e-13).
constexpr double kFinestShare = 1e-14;

// Pieces between events narrower than this (radians) contribute at most 1e-7 of a meridian's integrand;
// kinks inside them are not located.
constexpr double kNarrowPiece = 1e-7;

// Hidden stretches shorter than this (in the segment's parameter, 0..1) are ignored: see inside_interval.
constexpr double kNegligibleStretch = 1e-12;

// Three-point Gauss-Legendre on [-1, 1]: exact for polynomials up to degree 5, which covers every
// integrand of the stump pieces (at most degree 4 in the axial coordinate, degree 3 along a segment).
constexpr std::array<double, 3> kGL3Nodes = {-0.774596669241483377035853079956480, 0.0,
                                             0.774596669241483377035853079956480};
constexpr std::array<double, 3> kGL3Weights = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

template <class F>
double gauss3(double lo, double hi, const F& f) {
  const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) sum += kGL3Weights[k] * f(mid + half * kGL3Nodes[k]);
  return half * sum;
}

struct Cone {
  double sin_phi = 0.0, cos_phi = 1.0;
  double radius_at(double r, double x) const { return (r - x * sin_phi) / cos_phi; }
};

Cone cone_of(const HubStump& s) {
  Cone c;
  c.sin_phi = (s.radius - s.other_radius) / s.length;
  c.cos_phi = std::sqrt((1.0 - c.sin_phi) * (1.0 + c.sin_phi));
  return c;
}

Vec3 any_perpendicular(const Vec3& n) {
  const Vec3 helper = std::abs(n.x) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  return glm::normalize(helper - glm::dot(helper, n) * n);
}

// One stump's derived geometry, in its meridian half-plane (axial x, radial y) from the node center.
struct StumpGeometry {
  HubStump s;
  Cone cone;
  double exit_x = 0.0, exit_y = 0.0;  // where the cone leaves the node sphere
  double cut_x = 0.0, cut_y = 0.0;    // rim of the cut disk
  double tangent_x = 0.0;             // near tangent circle: the cone part of the beam starts there
  double half_angle = 0.0;            // of the cap
  double rim_angle = 0.0;             // direction of the cut rim
  Vec3 e1{0.0}, e2{0.0};              // completes the axis to a right-handed frame
};

StumpGeometry geometry_of(double R, const HubStump& s) {
  StumpGeometry g;
  g.s = s;
  g.cone = cone_of(s);
  const double r = s.radius;
  g.exit_x = r * g.cone.sin_phi + g.cone.cos_phi * std::sqrt(std::max(0.0, (R - r) * (R + r)));
  g.exit_y = g.cone.radius_at(r, g.exit_x);
  g.cut_x = s.cut_position();
  g.cut_y = g.cone.radius_at(r, g.cut_x);
  g.tangent_x = r * g.cone.sin_phi;
  g.half_angle = std::atan2(g.exit_y, g.exit_x);
  g.rim_angle = std::atan2(g.cut_y, g.cut_x);
  g.e1 = any_perpendicular(s.axis);
  g.e2 = glm::cross(s.axis, g.e1);
  return g;
}

std::string stump_field(std::size_t index) { return "hub.stumps[" + std::to_string(index) + "]"; }

// ---- direction-space quadrature over one stump's cap -------------------------------------------------

// A neighbouring stump j seen in stump i's frame (n_i, e1_i, e2_i).
struct Neighbour {
  double along = 0.0;       // n_i . n_j
  double b1 = 0.0, b2 = 0.0;  // e1_i . n_j, e2_i . n_j
  double sin_phi = 0.0, cos2_phi = 1.0, radius = 0.0, cut_x = 0.0, tangent_x = 0.0;
};

// Components of one meridian's integrand (per unit meridian angle), in stump i's frame.
enum Component { kVolume, kFirstX, kFirstY, kFirstZ, kXX, kXY, kXZ, kYY, kYZ, kZZ, kConeArea, kCutArea, kSolid, kCount };
using Integrand = std::array<double, kCount>;

// What bounds a hidden stretch at one end: the segment's end, one of j's planes, or j's cone.
enum Bound : std::uint8_t { kSegmentEnd, kCutPlane, kTangentPlane, kApexPlane, kConeSurface };

struct Interval {
  double lo, hi;
  std::uint8_t lo_bound = kSegmentEnd, hi_bound = kSegmentEnd;
  std::uint8_t neighbour = 0;
};

// Requires alpha + beta t <= 0 on [lo, hi]; records which bound tightened.
void clip_linear(double alpha, double beta, Interval& iv, Bound bound) {
  if (beta > 0.0) {
    const double t = -alpha / beta;
    if (t < iv.hi) {
      iv.hi = t;
      iv.hi_bound = bound;
    }
  } else if (beta < 0.0) {
    const double t = -alpha / beta;
    if (t > iv.lo) {
      iv.lo = t;
      iv.lo_bound = bound;
    }
  } else if (alpha > 0.0) {
    iv.hi = iv.lo - 1.0;  // empty
  }
}

// The parameters t in [0, 1] of the segment (X0 + t dX, Y0 + t dY) of the meridian half-plane (direction
// cos psi e1 + sin psi e2 for the radial coordinate) that lie inside stump j. S_j is convex, so this is one
// interval. Outside the node ball, S_j is { tangent_x <= x_j <= cut_x, x_j sin(phi) + rho_j cos(phi) <= r }.
bool inside_interval(const Neighbour& nb, double bpsi, double X0, double Y0, double dX, double dY, Interval& out) {
  const double x0 = X0 * nb.along + Y0 * bpsi, dx = dX * nb.along + dY * bpsi;
  Interval iv{0.0, 1.0};
  clip_linear(x0 - nb.cut_x, dx, iv, kCutPlane);
  clip_linear(nb.tangent_x - x0, -dx, iv, kTangentPlane);
  clip_linear(x0 * nb.sin_phi - nb.radius, dx * nb.sin_phi, iv, kApexPlane);  // r - x sin(phi) >= 0: the right nappe
  if (!(iv.hi > iv.lo)) return false;
  // rho_j^2 cos^2(phi) - (r - x_j sin(phi))^2 <= 0, with rho_j^2 = |q|^2 - x_j^2.
  const double h0 = nb.radius - x0 * nb.sin_phi, dh = -dx * nb.sin_phi;
  const double a2 = nb.cos2_phi * (dX * dX + dY * dY - dx * dx) - dh * dh;
  const double a1 = 2.0 * (nb.cos2_phi * (X0 * dX + Y0 * dY - x0 * dx) - h0 * dh);
  const double a0 = nb.cos2_phi * (X0 * X0 + Y0 * Y0 - x0 * x0) - h0 * h0;
  Interval in = iv;
  if (a2 == 0.0) {
    clip_linear(a0, a1, in, kConeSurface);
  } else {
    const double disc = a1 * a1 - 4.0 * a2 * a0;
    if (disc < 0.0) {
      if (a2 > 0.0) return false;  // positive everywhere: outside
      // negative everywhere: inside on all of [lo, hi]
    } else {
      const double q = -0.5 * (a1 + std::copysign(std::sqrt(disc), a1));
      double r1 = q / a2, r2 = q != 0.0 ? a0 / q : 0.0;
      if (r1 > r2) std::swap(r1, r2);
      auto raise_lo = [&](double t) {
        if (t > in.lo) {
          in.lo = t;
          in.lo_bound = kConeSurface;
        }
      };
      auto lower_hi = [&](double t) {
        if (t < in.hi) {
          in.hi = t;
          in.hi_bound = kConeSurface;
        }
      };
      if (a2 > 0.0) {
        raise_lo(r1);
        lower_hi(r2);
      } else {
        // Outside the roots; the set is convex, so at most one side meets [lo, hi] (hull if rounding says both).
        const bool left = std::min(iv.hi, r1) > iv.lo, right = iv.hi > std::max(iv.lo, r2);
        if (left && !right) {
          lower_hi(r1);
        } else if (right && !left) {
          raise_lo(r2);
        } else if (!left && !right) {
          return false;
        }
      }
    }
  }
  // Near a tangency the stretch can flicker in and out of existence with rounding; one this short changes
  // the integrand by less than 1e-12 of the segment's share, so it is ignored (and kept out of the signature).
  if (!(in.hi - in.lo > kNegligibleStretch)) return false;
  out = in;
  return true;
}

class CapIntegrand {
 public:
  CapIntegrand(const StumpGeometry& g, double node_radius, std::vector<Neighbour> neighbours)
      : g_(g), R_(node_radius), neighbours_(std::move(neighbours)) {}

  // The integrand at meridian psi, with a signature of which bounds delimit the hidden stretches.
  detail::Sample<kCount> operator()(double psi) const {
    detail::Sample<kCount> sample;
    Integrand& out = sample.value;
    std::uint64_t signature = 1469598103934665603ull;  // FNV-1a
    auto mix = [&signature](std::uint64_t v) { signature = (signature ^ v) * 1099511628211ull; };
    const double c = std::cos(psi), s = std::sin(psi);
    const double segments[2][4] = {{g_.exit_x, g_.exit_y, g_.cut_x - g_.exit_x, g_.cut_y - g_.exit_y},
                                   {g_.cut_x, g_.cut_y, 0.0, -g_.cut_y}};
    for (int seg = 0; seg < 2; ++seg) {
      const double X0 = segments[seg][0], Y0 = segments[seg][1], dX = segments[seg][2], dY = segments[seg][3];
      if (dX == 0.0 && dY == 0.0) continue;
      hidden_.clear();
      for (std::size_t j = 0; j < neighbours_.size(); ++j) {
        const Neighbour& nb = neighbours_[j];
        Interval iv;
        if (inside_interval(nb, nb.b1 * c + nb.b2 * s, X0, Y0, dX, dY, iv)) {
          iv.neighbour = static_cast<std::uint8_t>(j);
          hidden_.push_back(iv);
        }
      }
      std::sort(hidden_.begin(), hidden_.end(), [](const Interval& a, const Interval& b) { return a.lo < b.lo; });
      mix(0xff00 + seg);
      double t = 0.0;
      std::uint64_t reach = 0;  // which bound of which neighbour ends the current hidden block
      for (const Interval& iv : hidden_) {
        if (iv.lo > t) {
          add_visible(out, seg == 0, X0, Y0, dX, dY, t, iv.lo, c, s);
          mix(reach);
          mix(0x100 + 8 * iv.neighbour + iv.lo_bound);
        }
        if (iv.hi > t) {
          t = iv.hi;
          reach = 0x10000 + 8 * iv.neighbour + iv.hi_bound;
        }
      }
      mix(reach);
      if (t < 1.0) add_visible(out, seg == 0, X0, Y0, dX, dY, t, 1.0, c, s);
    }
    sample.signature = signature;
    return sample;
  }

 private:
  // Adds the visible stretch [t0, t1] of a segment: the stump's surface there, minus the ball it hides.
  void add_visible(Integrand& out, bool cone, double X0, double Y0, double dX, double dY, double t0, double t1,
                   double c, double s) const {
    // Along a line, d(theta)/dt = C / |q|^2 with C = q x q' constant, and sin(theta) = Y/|q|, so
    // rho^(3+n)/(3+n) u^n sin(theta) d(theta) = |C|/(3+n) Y (q/1)^n dt: polynomials in t.
    const double absC = std::abs(X0 * dY - Y0 * dX);
    const double seg_len = std::hypot(dX, dY);
    const double mid = 0.5 * (t0 + t1), half = 0.5 * (t1 - t0);
    for (int k = 0; k < 3; ++k) {
      const double t = mid + half * kGL3Nodes[k], w = half * kGL3Weights[k];
      const double X = X0 + t * dX, Y = Y0 + t * dY;
      const double q[3] = {X, Y * c, Y * s};
      const double wv = w * absC * Y;
      out[kVolume] += wv / 3.0;
      for (int a = 0; a < 3; ++a) out[kFirstX + a] += wv / 4.0 * q[a];
      out[kXX] += wv / 5.0 * q[0] * q[0];
      out[kXY] += wv / 5.0 * q[0] * q[1];
      out[kXZ] += wv / 5.0 * q[0] * q[2];
      out[kYY] += wv / 5.0 * q[1] * q[1];
      out[kYZ] += wv / 5.0 * q[1] * q[2];
      out[kZZ] += wv / 5.0 * q[2] * q[2];
      out[cone ? kConeArea : kCutArea] += w * Y * seg_len;
    }
    // The ball's radial function R over the same directions, subtracted: closed-form trigonometric integrals.
    const double th_a = std::atan2(Y0 + t0 * dY, X0 + t0 * dX), th_b = std::atan2(Y0 + t1 * dY, X0 + t1 * dX);
    const double lo = std::min(th_a, th_b), hi = std::max(th_a, th_b);
    const double c0 = std::cos(lo), c1 = std::cos(hi), s0 = std::sin(lo), s1 = std::sin(hi);
    const double omega = c0 - c1;                                    // int sin
    const double i_cs = 0.5 * (s1 * s1 - s0 * s0);                    // int cos sin
    const double i_ss = 0.5 * ((hi - lo) - (s1 * c1 - s0 * c0));      // int sin^2
    const double i_ccs = (c0 * c0 * c0 - c1 * c1 * c1) / 3.0;         // int cos^2 sin
    const double i_css = (s1 * s1 * s1 - s0 * s0 * s0) / 3.0;         // int cos sin^2
    const double i_sss = omega - i_ccs;                               // int sin^3
    const double R3 = R_ * R_ * R_, R4 = R3 * R_, R5 = R4 * R_;
    out[kSolid] += omega;
    out[kVolume] -= R3 / 3.0 * omega;
    out[kFirstX] -= R4 / 4.0 * i_cs;
    out[kFirstY] -= R4 / 4.0 * c * i_ss;
    out[kFirstZ] -= R4 / 4.0 * s * i_ss;
    out[kXX] -= R5 / 5.0 * i_ccs;
    out[kXY] -= R5 / 5.0 * c * i_css;
    out[kXZ] -= R5 / 5.0 * s * i_css;
    out[kYY] -= R5 / 5.0 * c * c * i_sss;
    out[kYZ] -= R5 / 5.0 * c * s * i_sss;
    out[kZZ] -= R5 / 5.0 * s * s * i_sss;
  }

  const StumpGeometry& g_;
  double R_;
  std::vector<Neighbour> neighbours_;
  mutable std::vector<Interval> hidden_;
};

double wrap_angle(double a) {
  a = std::fmod(a, 2.0 * kPi);
  return a < 0.0 ? a + 2.0 * kPi : a;
}

// Where, as the meridian angle psi turns, neighbour j starts or stops hiding part of one profile segment of
// stump i. Along the segment everything about j depends on psi only through beta = m(psi) . n_j, and the
// hidden stretch [max of lower bounds, min of upper bounds] can only appear or vanish where two of its
// bounds meet: a root of the quadratic Q (rho_j^2 cos^2 - (r - x_j sin)^2) at a segment end (Q(0), Q(1)),
// at one of j's planes (cut, tangent circle, apex: Q(t_plane) dx^2), the two roots of Q merging (its
// discriminant: the segment grazes j's cone, a square-root singularity), or a plane reaching a segment
// end or turning parallel to it. All are polynomials of degree <= 4 in beta, solved exactly; each root
// gives two meridians. Between consecutive events no hidden stretch appears or vanishes, so the
// quadrature cannot miss a narrow one.
void add_events(const StumpGeometry& gi, const Neighbour& nb, std::vector<double>& out) {
  using detail::Quartic;
  const double sin_gamma = std::hypot(nb.b1, nb.b2);
  if (!(sin_gamma > 1e-12)) return;  // coaxial: nothing depends on psi
  const double psi_j = std::atan2(nb.b2, nb.b1);
  const double segments[2][4] = {{gi.exit_x, gi.exit_y, gi.cut_x - gi.exit_x, gi.cut_y - gi.exit_y},
                                 {gi.cut_x, gi.cut_y, 0.0, -gi.cut_y}};
  std::vector<Quartic> events;
  for (const auto& seg : segments) {
    const double X0 = seg[0], Y0 = seg[1], dX = seg[2], dY = seg[3];
    const Quartic x0 = Quartic::linear(X0 * nb.along, Y0), dx = Quartic::linear(dX * nb.along, dY);
    const double cos2 = nb.cos2_phi, r = nb.radius, s = nb.sin_phi;
    // Q(t) = A2 t^2 + A1 t + A0 (using cos^2 + sin^2 = 1)
    const Quartic a2 = Quartic::constant(cos2 * (dX * dX + dY * dY)) - dx * dx;
    const Quartic a1 = 2.0 * (Quartic::constant(cos2 * (X0 * dX + Y0 * dY)) - x0 * dx + (r * s) * dx);
    const Quartic a0 = Quartic::constant(cos2 * (X0 * X0 + Y0 * Y0) - r * r) - x0 * x0 + (2.0 * r * s) * x0;
    events.push_back(a0);
    events.push_back(a2 + a1 + a0);
    events.push_back(a1 * a1 - 4.0 * (a2 * a0));
    events.push_back(dx);
    std::vector<double> planes{nb.cut_x, nb.tangent_x};
    if (s != 0.0) planes.push_back(r / s);  // the apex of j's cone
    for (double c : planes) {
      const Quartic gap = Quartic::constant(c) - x0;  // t_plane = gap / dx
      events.push_back(a2 * gap * gap + a1 * gap * dx + a0 * dx * dx);
      events.push_back(gap);
      events.push_back(gap - dx);
    }
  }
  for (const Quartic& p : events)
    for (double beta : detail::roots_in(p, -sin_gamma, sin_gamma)) {
      const double delta = std::acos(std::clamp(beta / sin_gamma, -1.0, 1.0));
      out.push_back(wrap_angle(psi_j + delta));
      out.push_back(wrap_angle(psi_j - delta));
    }
}

StumpContribution integrate_cap(const std::vector<StumpGeometry>& all, std::size_t i, const std::vector<std::size_t>& near,
                                double R, const Integrand& scale, double tolerance, double* error) {
  const StumpGeometry& gi = all[i];
  std::vector<Neighbour> neighbours;
  std::vector<double> breaks;
  for (std::size_t j : near) {
    const StumpGeometry& gj = all[j];
    Neighbour nb;
    nb.along = glm::dot(gi.s.axis, gj.s.axis);
    nb.b1 = glm::dot(gi.e1, gj.s.axis);
    nb.b2 = glm::dot(gi.e2, gj.s.axis);
    nb.sin_phi = gj.cone.sin_phi;
    nb.cos2_phi = gj.cone.cos_phi * gj.cone.cos_phi;
    nb.radius = gj.s.radius;
    nb.cut_x = gj.cut_x;
    nb.tangent_x = gj.tangent_x;
    neighbours.push_back(nb);
    add_events(gi, nb, breaks);
  }
  breaks.push_back(0.0);
  breaks.push_back(2.0 * kPi);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  // Piece k of [0, 2 pi] between consecutive events becomes [k, k + 1] in u, with psi = a + (b - a) S(u - k)
  // and S(s) = 3 s^2 - 2 s^3: a square-root singularity at an event becomes smooth in u.
  const CapIntegrand f(gi, R, std::move(neighbours));
  auto graded = [&](double u) {
    const std::size_t k = std::min(static_cast<std::size_t>(u), breaks.size() - 2);
    const double s = u - static_cast<double>(k), a = breaks[k], width = breaks[k + 1] - a;
    detail::Sample<kCount> v = f(a + width * s * s * (3.0 - 2.0 * s));
    const double jacobian = width * 6.0 * s * (1.0 - s);
    for (double& x : v.value) x *= jacobian;
    if (width < kNarrowPiece) v.signature = 0;  // its kinks cannot matter; do not chase rounding flicker
    return v;
  };
  std::vector<double> integers;
  for (std::size_t k = 1; k + 1 < breaks.size(); ++k) integers.push_back(static_cast<double>(k));
  const auto result = detail::integrate_adaptive<kCount>(graded, 0.0, static_cast<double>(breaks.size() - 1),
                                                         integers, scale, tolerance, kKinkResolution);
  *error += result.error;
  const Integrand& v = result.value;
  // Back from the stump's frame (n, e1, e2) to the hub's axes.
  Mat3 basis;
  basis[0] = gi.s.axis;
  basis[1] = gi.e1;
  basis[2] = gi.e2;
  Mat3 local;
  local[0][0] = v[kXX];
  local[1][1] = v[kYY];
  local[2][2] = v[kZZ];
  local[0][1] = local[1][0] = v[kXY];
  local[0][2] = local[2][0] = v[kXZ];
  local[1][2] = local[2][1] = v[kYZ];
  StumpContribution c;
  c.moments.volume = v[kVolume];
  c.moments.first = basis * Vec3(v[kFirstX], v[kFirstY], v[kFirstZ]);
  c.moments.second = basis * local * glm::transpose(basis);
  c.cone_area = v[kConeArea];
  c.cut_area = v[kCutArea];
  c.solid_angle = v[kSolid];
  c.moments.area = c.cone_area - R * R * c.solid_angle;
  return c;
}

}  // namespace

HubShape hub_shape(const Hub& hub) {
  HubShape h;
  h.center = hub.ball.center;
  h.radius = hub.ball.radius;
  for (const Stump& s : hub.stumps)
    h.stumps.push_back({s.cone.axis, s.cone.length, s.cone.ra, s.cone.rb, s.cut_position});
  return h;
}

StumpCap stump_cap(double node_radius, const HubStump& stump) {
  const StumpGeometry g = geometry_of(node_radius, stump);
  return {g.exit_x, g.half_angle};
}

MassMoments ball_moments(double radius) {
  MassMoments m;
  const double r2 = radius * radius, r3 = r2 * radius;
  m.volume = 4.0 / 3.0 * kPi * r3;
  m.second = (4.0 / 15.0 * kPi * r3 * r2) * Mat3(1.0);
  m.area = 4.0 * kPi * r2;
  return m;
}

StumpContribution stump_contribution_alone(double R, const HubStump& stump) {
  const StumpGeometry g = geometry_of(R, stump);
  const double r = stump.radius;
  auto rho = [&](double x) { return g.cone.radius_at(r, x); };
  // Frustum from the exit circle to the cut, minus the cap of the ball beyond the exit plane.
  const double x0 = g.exit_x, x1 = g.cut_x;
  const double volume = kPi * (gauss3(x0, x1, [&](double x) { return rho(x) * rho(x); }) -
                               gauss3(x0, R, [&](double x) { return (R - x) * (R + x); }));
  const double axial_first = kPi * (gauss3(x0, x1, [&](double x) { return x * rho(x) * rho(x); }) -
                                    gauss3(x0, R, [&](double x) { return x * (R - x) * (R + x); }));
  const double axial_second = kPi * (gauss3(x0, x1, [&](double x) { return x * x * rho(x) * rho(x); }) -
                                     gauss3(x0, R, [&](double x) { return x * x * (R - x) * (R + x); }));
  const double radial_second =
      0.5 * kPi * (gauss3(x0, x1, [&](double x) { return std::pow(rho(x), 4); }) -
                   gauss3(x0, R, [&](double x) { return (R - x) * (R + x) * (R - x) * (R + x); }));
  StumpContribution c;
  c.cone_area = 2.0 * kPi / g.cone.cos_phi * gauss3(x0, x1, rho);
  c.cut_area = kPi * g.cut_y * g.cut_y;
  c.solid_angle = 2.0 * kPi * (1.0 - x0 / R);
  const double covered = 2.0 * kPi * R * (R - x0);
  c.moments = axisymmetric_moments(stump.axis, volume, axial_first, axial_second, radial_second, c.cone_area - covered);
  return c;
}

void validate_hub_shape(const HubShape& hub) {
  for (int c = 0; c < 3; ++c) require_finite(hub.center[c], "hub.center");
  require_positive(hub.radius, "hub.radius");
  for (std::size_t k = 0; k < hub.stumps.size(); ++k) {
    const HubStump& s = hub.stumps[k];
    const std::string f = stump_field(k);
    require_positive(s.length, f + ".length");
    require_positive(s.radius, f + ".radius");
    require_positive(s.other_radius, f + ".other_radius");
    if (!(std::abs(glm::length(s.axis) - 1.0) < 1e-9)) fail_input(f + ".axis", "must be a unit vector");
    if (s.radius > hub.radius * (1.0 + kMidPlaneSlack))
      fail_input(f + ".radius", "exceeds the node radius: the beam would stick out of its node");
    if (!(std::abs(s.radius - s.other_radius) < s.length))
      fail_input(f, "one end ball of the beam contains the other: the beam has no cone");
    if (!(s.cut >= 0.0 && s.cut < s.length)) fail_input(f + ".cut", "must lie between the beam's two nodes");
    // The cut may lie inside the ball (a crowded hub's collar) as long as its rim lies outside, beyond the exit.
    const double cut = s.cut_position();
    const StumpGeometry g = geometry_of(hub.radius, s);
    if (!(g.cut_x > g.exit_x * (1.0 + kMidPlaneSlack)))
      fail_input(f, "the node ball (radius " + std::to_string(hub.radius) + ") holds the beam's whole cut (at " +
                        std::to_string(cut) + "): the lattice is not clean there");
    const Cone cone = cone_of(s);
    if (s.length + s.other_radius * cone.sin_phi < cut)
      fail_input(f, "the far end ball of the beam crosses the beam's cut: the lattice is not clean there");
  }
}

bool stump_caps_overlap(double R, const HubStump& a, const HubStump& b) {
  const double gamma = std::atan2(glm::length(glm::cross(a.axis, b.axis)), glm::dot(a.axis, b.axis));
  return gamma < stump_cap(R, a).half_angle + stump_cap(R, b).half_angle - kCapOverlapMargin;
}

HubProperties hub_properties(const HubShape& hub, const HubPropertiesOptions& options) {
  validate_hub_shape(hub);
  const double R = hub.radius;
  const std::size_t m = hub.stumps.size();
  std::vector<StumpGeometry> geometry;
  geometry.reserve(m);
  for (const HubStump& s : hub.stumps) geometry.push_back(geometry_of(R, s));

  HubProperties out;
  out.moments = ball_moments(R);
  out.stumps.resize(m);
  std::vector<std::vector<std::size_t>> near(m);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = i + 1; j < m; ++j)
      if (stump_caps_overlap(R, hub.stumps[i], hub.stumps[j])) {
        near[i].push_back(j);
        near[j].push_back(i);
      }
  // Scales of the quadrature's error: the hub's size as if no caps overlapped.
  double volume_scale = out.moments.volume, area_scale = out.moments.area, length_scale = R;
  for (std::size_t i = 0; i < m; ++i) {
    out.stumps[i] = stump_contribution_alone(R, hub.stumps[i]);
    volume_scale += std::max(0.0, out.stumps[i].moments.volume);
    area_scale += out.stumps[i].cone_area + out.stumps[i].cut_area;
    length_scale = std::max(length_scale, std::hypot(geometry[i].cut_x, geometry[i].cut_y));
  }
  Integrand scale{};
  scale[kVolume] = volume_scale;
  for (int a = kFirstX; a <= kFirstZ; ++a) scale[a] = volume_scale * length_scale;
  for (int a = kXX; a <= kZZ; ++a) scale[a] = volume_scale * length_scale * length_scale;
  scale[kConeArea] = scale[kCutArea] = area_scale;
  scale[kSolid] = 4.0 * kPi;
  // The tolerance is the hub's: shared evenly by the caps integrated numerically.
  std::size_t integrated = 0;
  for (std::size_t i = 0; i < m; ++i) integrated += !near[i].empty() || options.quadrature_everywhere;
  const double share =
      std::max(kFinestShare, options.tolerance / static_cast<double>(std::max<std::size_t>(1, integrated)));
  double error = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    if (!near[i].empty() || options.quadrature_everywhere) {
      out.closed_form = false;
      out.stumps[i] = integrate_cap(geometry, i, near[i], R, scale, share, &error);
    }
    out.moments += out.stumps[i].moments;
  }
  out.error_estimate = error;
  return out;
}

bool any_stump_caps_overlap(const HubShape& hub) { return any_stump_caps_overlap(hub, 1.0); }

bool any_stump_caps_overlap(const HubShape& hub, double radius_scale) {
  const std::size_t m = hub.stumps.size();
  if (m < 2) return false;
  // Caps as (cos, sin) of their half-angles; gamma < a + b (both in [0, pi]) compared through cosines,
  // without trigonometric calls: the same decision as stump_caps_overlap (margin included).
  thread_local std::vector<std::pair<double, double>> caps;
  caps.resize(m);
  const double R = radius_scale * hub.radius;
  for (std::size_t i = 0; i < m; ++i) {
    const HubStump& st = hub.stumps[i];
    const double r = radius_scale * st.radius;
    const double sin_phi = radius_scale * (st.radius - st.other_radius) / st.length;
    const double cos_phi = std::sqrt((1.0 - sin_phi) * (1.0 + sin_phi));
    const double x = r * sin_phi + cos_phi * std::sqrt(std::max(0.0, (R - r) * (R + r)));
    const double y = (r - x * sin_phi) / cos_phi;
    const double len = std::hypot(x, y);
    caps[i] = {x / len, y / len};
  }
  const double cos_margin = std::cos(kCapOverlapMargin), sin_margin = std::sin(kCapOverlapMargin);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = i + 1; j < m; ++j) {
      // cos and sin of (a + b - margin)
      const double c_ab = caps[i].first * caps[j].first - caps[i].second * caps[j].second;
      const double s_ab = caps[i].second * caps[j].first + caps[i].first * caps[j].second;
      const double c_sum = c_ab * cos_margin + s_ab * sin_margin, s_sum = s_ab * cos_margin - c_ab * sin_margin;
      // gamma < a + b - margin  <=>  cos(gamma) > cos(a + b - margin) when a + b - margin is in [0, pi];
      // beyond pi every gamma is smaller (overlap), below 0 none is.
      if (s_sum < 0.0) {
        if (c_sum < 0.0) return true;  // a + b - margin > pi
        continue;                      // a + b - margin < 0
      }
      if (glm::dot(hub.stumps[i].axis, hub.stumps[j].axis) > c_sum) return true;
    }
  return false;
}

MassMoments hub_overlap_correction(const HubShape& hub, const HubPropertiesOptions& options) {
  if (!any_stump_caps_overlap(hub)) return {};
  const HubProperties p = hub_properties(hub, options);
  MassMoments correction = p.moments - ball_moments(hub.radius);
  for (const HubStump& s : hub.stumps) correction -= stump_contribution_alone(hub.radius, s).moments;
  return correction;
}

}  // namespace steady
