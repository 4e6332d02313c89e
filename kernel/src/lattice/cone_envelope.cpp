#include "lattice/cone_envelope.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lattice/circle_frames.hpp"
#include "steady/core/errors.hpp"

namespace steady::hull {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;

// Solutions u of a0 + a1 cos u + a2 sin u = 0.
void trig_roots(double a0, double a1, double a2, std::vector<double>& out) {
  const double r = std::hypot(a1, a2);
  if (!(r > 1e-15) || std::abs(a0) > r) return;
  const double phi = std::atan2(a2, a1), beta = std::acos(std::clamp(-a0 / r, -1.0, 1.0));
  out.push_back(phi + beta);
  out.push_back(phi - beta);
}

// A piece whose two ends merged into one vertex (a neighbour active over less than kVertexMerge, where a slight
// perturbation splits a point at which four stumps meet) has no edge to carry: as an arc from a vertex back to
// itself it would be read as the whole conic. Its partner cone drops the same piece (same vertices), so the faces
// still agree; the vertex then joins the pieces on either side. Neighbours left with the same active merge.
void drop_pieces_without_length(Envelope& env) {
  std::vector<Piece>& p = env.pieces;
  if (p.size() < 2) return;
  std::vector<Piece> kept;
  for (const Piece& q : p) {
    if (q.v0 == q.v1) continue;
    if (!kept.empty() && kept.back().active == q.active) {
      kept.back().u1 = q.u1;
      kept.back().v1 = q.v1;
    } else {
      kept.push_back(q);
    }
  }
  if (kept.size() > 1 && kept.front().active == kept.back().active) {
    kept.front().u0 = kept.back().u0 - kTwoPi;
    kept.front().v0 = kept.back().v0;
    kept.pop_back();
  }
  if (kept.empty()) fail_input("hub", "a stump's envelope has no piece longer than the vertex tolerance");
  // The pieces stay contiguous in u: each starts where the one before it ends.
  for (std::size_t k = 0; k + 1 < kept.size(); ++k) kept[k].u1 = kept[k + 1].u0;
  kept.back().u1 = kept.front().u0 + kTwoPi;
  p = kept;
  env.window = p.front().u0;
}

// The envelope of cone i: its pieces between breakpoints, merged where the active neighbour stays the same.
Envelope envelope_of(const std::vector<Cone>& cones, int i, double v_collar, double clearance, VertexPool& pool) {
  const Cone& ki = cones[i];
  std::vector<double> us = breakpoint_candidates(cones, i);
  // Validity along the whole circle: the envelope stays below the collar, the ceilings above it.
  std::vector<double> probes = us;
  for (int k = 0; k < kEnvelopeProbes; ++k) probes.push_back(kTwoPi * k / kEnvelopeProbes);
  for (double u : probes) {
    const Active a = envelope_at(cones, i, u);
    if (!(a.v < v_collar - clearance) || !(ceiling_at(cones, i, u) > v_collar + clearance))
      fail_input("hub", "a stump is swallowed by its neighbours up to its collar");
  }
  Envelope env;
  if (us.empty()) us = {0.0};
  // Active stump on each interval between candidates; merge equal neighbours.
  struct Run {
    int active;
    double u0, u1;
  };
  std::vector<Run> runs;
  for (std::size_t k = 0; k < us.size(); ++k) {
    const double a = us[k], b = k + 1 < us.size() ? us[k + 1] : us[0] + kTwoPi;
    if (b - a < 1e-13) continue;
    const int act = envelope_at(cones, i, 0.5 * (a + b)).index;
    if (!runs.empty() && runs.back().active == act)
      runs.back().u1 = b;
    else
      runs.push_back({act, a, b});
  }
  if (runs.size() > 1 && runs.front().active == runs.back().active) {
    runs.front().u0 = runs.back().u0 - kTwoPi;
    runs.pop_back();
  }
  if (runs.size() == 1) {
    // One stump (or the sphere) all around: a closed edge, its vertex put at u = u0 by the face that makes it.
    env.window = runs[0].u0;
    env.pieces.push_back({runs[0].active, runs[0].u0, runs[0].u0 + kTwoPi, -1, -1});
    return env;
  }
  env.window = runs[0].u0;
  for (const Run& r : runs) {
    Piece p{r.active, r.u0, r.u1, -1, -1};
    p.v0 = pool.find_or_add(ki.point(r.u0, envelope_at(cones, i, r.u0).v));
    env.pieces.push_back(p);
  }
  for (std::size_t k = 0; k < env.pieces.size(); ++k) env.pieces[k].v1 = env.pieces[(k + 1) % env.pieces.size()].v0;
  // Vertex positions at breakpoints are the envelope's value there, which both neighbouring actives share.
  drop_pieces_without_length(env);
  return env;
}

}  // namespace

Vec3 Cone::point(double u, double v) const {
  return s * d + (c - v * s) * (std::cos(u) * e + std::sin(u) * f) + v * c * d;
}

double Cone::w(const Vec3& x) const { return (glm::dot(d, x) - s) / c; }

double Cone::u_of(const Vec3& x) const { return std::atan2(glm::dot(x, f), glm::dot(x, e)); }

Cone make_cone(const Vec3& direction, double sin_phi, double exit_v) {
  Cone k;
  k.exit_v = exit_v;
  k.d = glm::normalize(direction);
  k.e = any_perpendicular(k.d);
  k.f = glm::cross(k.d, k.e);
  k.s = sin_phi;
  k.c = std::sqrt((1.0 - k.s) * (1.0 + k.s));
  return k;
}

Bound bound_from(const Cone& ki, const Cone& kj, double u) {
  const Vec3 r = std::cos(u) * ki.e + std::sin(u) * ki.f;
  const double dd = glm::dot(kj.d, ki.d), dr = glm::dot(kj.d, r);
  const double A = ki.s * dd + ki.c * dr - kj.s;
  const double B = ki.c * dd - ki.s * dr;
  const double D = kj.c - B;
  if (D > 1e-14) return {Bound::Lower, A / D};
  if (D < -1e-14) return {Bound::Upper, A / D};
  return {A <= 0.0 ? Bound::Always : Bound::Never, 0.0};
}

Active envelope_at(const std::vector<Cone>& cones, int i, double u) {
  Active a{-1, cones[i].exit_v};
  for (int j = 0; j < static_cast<int>(cones.size()); ++j) {
    if (j == i) continue;
    const Bound b = bound_from(cones[i], cones[j], u);
    if (b.kind != Bound::Lower) continue;
    if (b.t > a.v + kTie || (a.index < 0 && b.t > a.v - kTie)) a = {j, std::max(a.v, b.t)};
  }
  return a;
}

double ceiling_at(const std::vector<Cone>& cones, int i, double u) {
  double top = std::numeric_limits<double>::infinity();
  for (int j = 0; j < static_cast<int>(cones.size()); ++j) {
    if (j == i) continue;
    const Bound b = bound_from(cones[i], cones[j], u);
    if (b.kind == Bound::Upper) top = std::min(top, b.t);
    if (b.kind == Bound::Never) top = -std::numeric_limits<double>::infinity();
  }
  return top;
}

// Where the active stump along the envelope of cone i can change: roots of the conditions of the candidates.
std::vector<double> breakpoint_candidates(const std::vector<Cone>& cones, int i) {
  const Cone& ki = cones[i];
  std::vector<double> us;
  const int n = static_cast<int>(cones.size());
  for (int j = 0; j < n; ++j) {
    if (j == i) continue;
    const Cone& kj = cones[j];
    const double dd = glm::dot(kj.d, ki.d), de = glm::dot(kj.d, ki.e), df = glm::dot(kj.d, ki.f);
    // A_j(u) = exit_v D_j(u): the bound of j crosses the exit circle (the tangent circle in the hull model).
    const double x = ki.exit_v;
    trig_roots(ki.s * dd - kj.s - x * (kj.c - ki.c * dd), (ki.c - x * ki.s) * de, (ki.c - x * ki.s) * df, us);
    // D_j(u) = 0: j switches between lower and upper bound.
    trig_roots(kj.c - ki.c * dd, ki.s * de, ki.s * df, us);
    for (int k = j + 1; k < n; ++k) {
      if (k == i) continue;
      // Points of cone i with w_i = w_j = w_k: the line of two planes meets the cone in up to two points.
      const Cone& kk = cones[k];
      const Vec3 n1 = ki.d / ki.c - kj.d / kj.c, n2 = ki.d / ki.c - kk.d / kk.c;
      const double b1 = ki.s / ki.c - kj.s / kj.c, b2 = ki.s / ki.c - kk.s / kk.c;
      const Vec3 q = glm::cross(n1, n2);
      const double qq = glm::dot(q, q);
      if (!(qq > 1e-24)) continue;
      const Vec3 p0 = (b1 * glm::cross(n2, q) + b2 * glm::cross(q, n1)) / qq;
      const double g = glm::dot(ki.d, q) / ki.c, w0 = ki.w(p0);
      const double A = qq - g * g, B = 2.0 * (glm::dot(p0, q) - w0 * g), C = glm::dot(p0, p0) - 1.0 - w0 * w0;
      std::vector<double> taus;
      if (std::abs(A) > 1e-14) {
        const double disc = B * B - 4 * A * C;
        if (disc < 0) continue;
        const double sq = std::sqrt(disc);
        taus = {(-B - sq) / (2 * A), (-B + sq) / (2 * A)};
      } else if (std::abs(B) > 1e-14) {
        taus = {-C / B};
      }
      for (double tau : taus) {
        const Vec3 x = p0 + tau * q;
        const double v = ki.w(x);
        if (v < ki.exit_v - 1e-9 || ki.c - v * ki.s <= 0.0) continue;  // inside the ball, or on the other nappe
        us.push_back(ki.u_of(x));
      }
    }
  }
  for (double& u : us) u = wrap_into(u, 0.0);
  std::sort(us.begin(), us.end());
  us.erase(std::unique(us.begin(), us.end(), [](double a, double b) { return std::abs(a - b) < 1e-13; }), us.end());
  return us;
}

int VertexPool::find_or_add(const Vec3& p) {
  for (std::size_t k = 0; k < points.size(); ++k)
    if (glm::length(points[k] - p) < kVertexMerge) return static_cast<int>(k);
  points.push_back(p);
  return static_cast<int>(points.size()) - 1;
}

Arrangement arrange_envelopes(const std::vector<Cone>& cones, const std::vector<double>& v_collar,
                              double clearance) {
  const int n = static_cast<int>(cones.size());
  Arrangement out;
  out.envelopes.resize(n);
  for (int i = 0; i < n; ++i) out.envelopes[i] = envelope_of(cones, i, v_collar[i], clearance, out.vertices);
  // Closed pieces (one active all around) get their vertex from the lower face; the partner face starts there.
  for (int i = 0; i < n; ++i) {
    Piece& p = out.envelopes[i].pieces[0];
    if (out.envelopes[i].pieces.size() != 1) continue;
    if (p.v0 >= 0) continue;
    const double u = p.u0;
    p.v0 = p.v1 = out.vertices.find_or_add(cones[i].point(u, envelope_at(cones, i, u).v));
    if (p.active >= 0) {
      const int j = p.active;
      if (out.envelopes[j].pieces.size() != 1 || out.envelopes[j].pieces[0].active != i)
        fail_input("hub", "two stumps disagree on their edge");
      const Vec3 x = out.vertices.points[p.v0];
      Piece& q = out.envelopes[j].pieces[0];
      q.u0 = wrap_into(cones[j].u_of(x), 0.0);
      q.u1 = q.u0 + kTwoPi;
      out.envelopes[j].window = q.u0;
      q.v0 = q.v1 = p.v0;
    }
  }
  return out;
}

}  // namespace steady::hull
