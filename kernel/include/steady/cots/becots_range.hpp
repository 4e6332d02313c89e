#pragma once
// The BeCOTS RangeFinder (Kurzeja's dissertation, chapter 8): which groups of a BeCOTS pattern of balls a query ball
// may meet, in time independent of the counts.
//
// The pattern: group (i, j), 0 <= i < nu, 0 <= j < nv, holds the template balls moved by the field S(i du, j dv) of a
// BeCOTS map (du = 1/(nu - 1) puts the last group on the corners, du = 1/nu tiles the range). In the map's log-polar
// coordinates about its apex, s = ln(|P - F| / |A - F|) and the azimuth theta about the axis, the field is a
// translation (by (x ln m_u + y ln m_v, x w_u + y w_v)), and the angle phi between P - F and the axis is invariant.
// A ball's log-polar bound is a rectangle in (s, theta) (the dissertation's "umbrella projection": the lines through
// the axis tangent to the ball and the spheres about F tangent to it) and an interval of phi (the conical shell).
// The rectangles of all groups are translates of the template's, so mapping the query's rectangle to parameters
// (x, y) (once per turn k of the azimuth) and comparing it with the template's gives rectangles of group indices:
// a superset of the groups that meet the query. Empty when the query misses the shell of cones the template spans.
#include <vector>

#include "steady/core/ball.hpp"
#include "steady/cots/becots_map.hpp"

namespace steady {

// Groups i0..i1 x j0..j1 (inclusive).
struct GroupRange {
  int i0 = 0, i1 = -1, j0 = 0, j1 = -1;
  bool empty() const { return i0 > i1 || j0 > j1; }
  long long count() const { return empty() ? 0 : static_cast<long long>(i1 - i0 + 1) * (j1 - j0 + 1); }
};

// A ball of the pattern: group (i, j) and the index of the template ball.
struct PatternBall {
  int i = 0, j = 0, n = 0;
};

class BecotsRangeFinder {
 public:
  // The pattern of `balls` placed by map.field(i du, j dv). Needs a map with an apex (not a flat parallelogram, whose
  // pattern is a translation lattice), template balls off the axis, counts >= 1 and steps > 0.
  BecotsRangeFinder(const BecotsMap& map, std::vector<Ball> balls, int nu, int nv, double du, double dv);

  // Rectangles of group indices holding every group with a ball that meets (or touches) `query`; several when the
  // range wraps around its axis. O(number of turns of the pattern about the axis), independent of nu and nv.
  std::vector<GroupRange> candidates(const Ball& query) const;
  // The balls that meet (or touch) `query`, testing only the candidates' balls.
  std::vector<PatternBall> interfering(const Ball& query) const;
  // The same by testing every ball of the pattern (the reference the tests compare with).
  std::vector<PatternBall> interfering_naive(const Ball& query) const;

  // The angles to the axis, seen from the apex, that a ball spans (the field keeps them: every group's balls lie in
  // the template's interval). `everything` when the ball holds the apex. A stack's layers are told apart by them.
  struct PolarInterval {
    double p0 = 0.0, p1 = 0.0;
    bool everything = true;
  };
  PolarInterval polar_interval() const { return {template_.p0, template_.p1, template_.everything}; }
  PolarInterval polar_interval(const Ball& b) const;

  Ball ball(int i, int j, int n) const;
  int nu() const { return nu_; }
  int nv() const { return nv_; }

 private:
  // A ball's bound: s in [s0, s1], theta in [t0, t1] (t1 - t0 = 2 pi when it touches the axis), phi in [p0, p1].
  struct Bound {
    double s0, s1, t0, t1, p0, p1;
    bool everything;  // the ball holds the apex: no bound
  };
  Bound bound_of(const Ball& b) const;
  Vec2 parameters_at(double s, double theta) const;
  void parameter_box(double s0, double s1, double t0, double t1, double* x0, double* x1, double* y0, double* y1) const;

  BecotsMap map_;
  std::vector<Ball> balls_;
  int nu_, nv_;
  double du_, dv_;
  Vec3 apex_{0.0};
  Bound template_{};
  double tx0_ = 0, tx1_ = 0, ty0_ = 0, ty1_ = 0;  // the template's bound in parameters
};

}  // namespace steady
