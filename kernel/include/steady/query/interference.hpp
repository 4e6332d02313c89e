#pragma once
// Exact interference predicates between a query ball (or point, or ray) and the two kinds of lattice
// elements: a ball, and a beam, the convex hull of two balls (BeamGeometry: in the hull model its end
// balls are the nodes, with explicit radii they are the smaller balls at the node centers).
//
// All sets are closed: a query that only touches an element meets it. The distance functions are exact
// Euclidean distances for points outside the element (0 on its boundary) and negative inside, so
// "query ball (c, r) meets element" is exactly "distance(c) <= r". These are the predicates every query
// path uses (naive, RangeFinder, blocks), so the paths can only differ in which candidates they test.
#include <limits>

#include "steady/core/ball.hpp"
#include "steady/lattice/lattice.hpp"

namespace steady {

// Signed distance from p to the ball.
double distance_to_ball(const Vec3& p, const Ball& ball);

// Signed distance from p to the convex hull of balls a and b (the "cone-sphere" distance of Barbier and
// Galin): outside the hull it is the Euclidean distance; inside it is negative (the depth below the
// nearest boundary piece: ball a, ball b or the cone). When one ball contains the other the hull is the
// larger ball.
double distance_to_hull(const Vec3& p, const Ball& a, const Ball& b);
inline double distance_to_beam(const Vec3& p, const BeamGeometry& beam) {
  return distance_to_hull(p, beam.start, beam.end);
}

inline bool ball_meets_ball(const Ball& query, const Ball& ball) {
  return distance_to_ball(query.center, ball) <= query.radius;
}
inline bool ball_meets_beam(const Ball& query, const BeamGeometry& beam) {
  return distance_to_beam(query.center, beam) <= query.radius;
}

constexpr double kNoHit = std::numeric_limits<double>::infinity();

// The smallest s >= 0 with origin + s * direction in the closed ball, or kNoHit. `direction` is a unit
// vector; an origin inside the ball gives 0.
double ray_enters_ball(const Vec3& origin, const Vec3& direction, const Ball& ball);

// The same for the convex hull of two balls: the entry point lies on one of the boundary pieces (sphere
// a, sphere b, or the cone between the two tangent circles), so it is the least valid hit among them.
double ray_enters_hull(const Vec3& origin, const Vec3& direction, const Ball& a, const Ball& b);
inline double ray_enters_beam(const Vec3& origin, const Vec3& direction, const BeamGeometry& beam) {
  return ray_enters_hull(origin, direction, beam.start, beam.end);
}

}  // namespace steady
