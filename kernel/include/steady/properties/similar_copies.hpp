#pragma once
// Sums over similar copies: the moments of the union of count copies T^0 X, T^1 X, ..., T^(count-1) X of
// a solid X (disjoint interiors), where T is a similarity.
//
// A similarity acts linearly on moments (transformed()), so the sum is the geometric series
// sum_k rho(T)^k applied to X's moments. It is evaluated by doubling,
//     S(2h) = S(h) + T^h . S(h),   S(2h + 1) = S(2h) + T^(2h) . X,
// with the powers T^h from the generator in closed form (Similarity::power): O(log count) operations, no
// division, hence no cancellation at scale 1 or angle 0 where the fixed-point forms of the papers blow up
// (the swirl's fixed point runs off to infinity as s -> 1). Every W is covered the same way: screw, swirl
// and all their degenerate kinds.
#include <cstdint>

#include "steady/properties/mass_moments.hpp"
#include "steady/core/similarity.hpp"

namespace steady {

// The matrix form of `s` acting on moments taken about `origin`: x -> s(x + origin) - origin.
SimilarityTransform transform_about(const Similarity& s, const Vec3& origin);
SimilarityTransform transform_about(const SimilarityTransform& s, const Vec3& origin);

// sum_{k = first}^{first + count - 1} step^k applied to `body` (moments about `origin`, result too).
MassMoments sum_of_copies(const Similarity& step, const Vec3& origin, const MassMoments& body, std::int64_t count,
                          std::int64_t first = 0);

// sum_{k < count} e^(k log_ratio) = expm1(count log_ratio) / expm1(log_ratio), count when log_ratio = 0:
// the scalar geometric series of the papers (volume: log_ratio = 3 ln s, area: 2 ln s), stable near s = 1.
double geometric_sum(double log_ratio, std::int64_t count);

// Whether the two similarities commute exactly: the Lie bracket of their generators is exactly zero (both
// translations; a rotation, screw or swirl and a translation along its axis given exactly parallel; one the
// identity; equal generators). Only then are rows of inter-group beams similar copies along a second direction.
bool exactly_commute(const Similarity& a, const Similarity& b);

}  // namespace steady
