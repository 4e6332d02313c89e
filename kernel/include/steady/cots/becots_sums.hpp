#pragma once
// Closed-form sums over a BeCOTS pattern of balls (group (i, j), i < nu, j < nv, is the template moved by
// map.field(i du, j dv), as in becots_range.hpp): the volume, area and centroid cost O(template balls), independent
// of the counts. The dissertation's eq. 4.13 (with the ratio d = the per-step scale squared or cubed, see the
// digest's consistency note) and, for the centroid, its conjecture made exact: the centres of one template ball's
// copies are F + s_ij Rot_T(theta_ij)(c - F), so their weighted sum splits into geometric series in
// s^3, s^4 (along the axis) and s^4 e^{i theta} (across it).
#include <vector>

#include "steady/core/ball.hpp"
#include "steady/cots/becots_map.hpp"

namespace steady {

// The sum over the groups of (the group's scale)^power, s_ij = m_u^{i du} m_v^{j dv}: a product of two geometric
// series, written so that it stays accurate as a ratio approaches 1 (then each factor tends to its count).
double becots_scale_sum(const BecotsMap& map, double power, int nu, int nv, double du, double dv);

struct PatternProperties {
  double volume = 0.0;
  double area = 0.0;
  Vec3 centroid{0.0};  // of the volume
};

// Volume, surface area and centroid of the pattern's balls, each ball counted whole: exact when the balls are
// pairwise disjoint (overlaps count twice otherwise). A parallelogram's field (no apex) is a translation lattice;
// its sums are the plain counts and the mean shift.
PatternProperties becots_ball_pattern_properties(const BecotsMap& map, const std::vector<Ball>& balls, int nu, int nv,
                                                 double du, double dv);

}  // namespace steady
