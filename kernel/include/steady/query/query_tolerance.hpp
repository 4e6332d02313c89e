#pragma once
// Numerical slacks of the queries (RangeFinder, block bounds) and the tolerance that decides which fast
// paths apply. Every slack only ever *adds* candidates; the exact tests then decide, so a generous slack
// costs a little time and never changes an answer.

namespace steady {

// Absolute widening (radians) of every rotation extent. atan2 and asin are accurate to ~1e-16, but asin
// amplifies the rounding of its argument by 1/sqrt(1 - x^2): 1e-9 covers shapes whose distance to the
// axis exceeds their radius by a relative 1e-14 or more; closer ones are treated as meeting the axis.
constexpr double kRangeAngleSlack = 1e-9;

// Absolute widening of ln|x - F| in dilation extents: the logarithm of a length computed with a relative
// rounding of a few 1e-16 is off by as much in absolute terms; 1e-12 leaves four orders of headroom.
constexpr double kRangeLogSlack = 1e-12;

// Relative widening of every normalized extent bound: the divisions by the step and the sums of the
// theorem round relative to the values (up to ~1e18 for the longest rows); 1e-12 is ~1e4 ulps.
constexpr double kRangeRelativeSlack = 1e-12;

// The query ball is inflated by kQueryInflation * L + kQueryInflationPerStep * (u + v + w) * L before
// any range or bound is computed (L: the distance scale of the lattice and the query). It covers the
// difference between an element as the lattice evaluates it (G W^k V^j U^i, powers from the generator)
// and as the fast paths predict it (canonical decompositions, conjugated steps): a few ulps of L per
// factor plus the rounding of k theta, which grows with the index.
constexpr double kQueryInflation = 1e-9;
constexpr double kQueryInflationPerStep = 1e-14;

// Two steps commute, or a step leaves another direction's normalized maps unchanged, when the mismatch
// is below this, relative to the lattice's distance scale (or absolute, for angles and log-scales).
// Exact constructions (regular, cylindrical lattices) give ~1e-15; 1e-10 accepts steps computed from
// typed frames while the mismatch it lets through, times the counts, stays far inside kQueryInflation.
constexpr double kConditionTolerance = 1e-10;

}  // namespace steady
