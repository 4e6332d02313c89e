#pragma once
// RangeFinder (Kurzeja & Rossignac, "RangeFinder: accelerating ball-interference queries against steady
// lattices"): which instances R_k = S^k(R_0), k in a range of indices, of a steady row may meet a query
// ball, in closed form, without iterating over the row.
//
// S is split canonically into two commuting primitives: a rotation about an axis, and a translation
// along that axis or a dilation about a point on it (screw or swirl; either part may be missing). Each
// primitive has a *normalized map* M from space to the reals with M(S(x)) = M(x) + 1:
//     translation  M(x) = ((x - P) . a) / d              (d: distance advanced per step along axis a)
//     dilation     M(x) = ln|x - F| / ln s                (F: the fixed point, s: the scale per step)
//     rotation     M(x) = angle(x) / theta + b 2 pi / |theta|   (angle about the axis from a reference
//                                                         direction, b any integer: the branch)
// The other primitive leaves each map unchanged (a rotation keeps axial positions and distances to a
// point of its axis; a translation along the axis or a dilation about a point on it keeps angles), so
// each map is normalized for the whole S. Element k then maps into [s0 + k, e0 + k] where [s0, e0] is
// the template's *extent* under M, and it can meet the query only if that interval overlaps the query's
// extent [sq, eq]: k in [ceil(sq - e0), floor(eq - s0)] (the paper's theorem).
//
// The rotation map is multi-valued: the query's extent exists in every branch, sq + b P, eq + b P with
// P = 2 pi / |theta|. Instead of the paper's two-branch rule (which misses the branch -1 case of the
// digest's counter-example and rows that wrap) every branch b whose window meets the row's index range
// is evaluated, so the answer is a list of disjoint ranges, one per wrap at most.
//
// Conservative by construction: extents are widened by a slack covering the rounding of logarithms,
// angles and divisions (see rangefinder.cpp); callers inflate the query ball to cover the rounding of
// the elements' own evaluation.
#include <cstdint>
#include <vector>

#include "steady/ball.hpp"
#include "steady/similarity.hpp"

namespace steady {

// A closed range of integer indices; empty when lo > hi.
struct IndexRange {
  std::int64_t lo = 0, hi = -1;
  bool empty() const { return lo > hi; }
  std::int64_t size() const { return empty() ? 0 : hi - lo + 1; }
};

IndexRange intersect(const IndexRange& a, const IndexRange& b);

// A set of indices as sorted, disjoint, non-adjacent closed ranges.
class IndexRanges {
 public:
  void clear() { ranges_.clear(); }
  // Appends a range (any order); call normalize() before reading when ranges were added out of order.
  void add(const IndexRange& r) {
    if (!r.empty()) ranges_.push_back(r);
  }
  void normalize();
  void intersect_with(const IndexRange& r);
  bool empty() const { return ranges_.empty(); }
  std::int64_t count() const;
  bool contains(std::int64_t k) const;
  const std::vector<IndexRange>& ranges() const { return ranges_; }
  // The smallest single range holding all of them (empty when there is none).
  IndexRange hull() const;

 private:
  std::vector<IndexRange> ranges_;
};

// An interval of normalized map values. lo may be -inf and hi +inf (a dilation's fixed point inside the
// shape); `full` marks a rotation extent that covers every angle (the axis meets the shape).
struct Extent {
  double lo = 0.0, hi = 0.0;
  bool full = false;
};

// The canonical decomposition of a row's incremental similarity S with the normalized maps of its
// primitives. Built from the group element of S (its principal logarithm), so only the map S matters.
class RowMotion {
 public:
  static RowMotion from(const Similarity& s);
  static RowMotion from(const SimilarityTransform& t);

  SimilarityKind kind() const { return kind_; }
  bool translates() const { return translates_; }  // translation or screw: the T-map applies
  bool dilates() const { return dilates_; }        // dilation or swirl: the D-map applies
  bool rotates() const { return rotates_; }        // rotation, screw or swirl: the R-map applies

  // Rotation and translation axis (unit) and a point on it (the fixed point F for a swirl or dilation).
  const Vec3& axis() const { return axis_; }
  const Vec3& point() const { return point_; }
  double angle() const { return angle_; }          // theta per step, in (0, pi]
  double step_distance() const { return step_; }   // d per step along the axis (translation, screw)
  double log_scale() const { return log_scale_; }  // ln s per step (dilation, swirl)

  // --- normalized maps: M(S(x)) = M(x) + 1 -------------------------------------------------------------
  double translation_map(const Vec3& x) const;
  double dilation_map(const Vec3& x) const;             // -inf or +inf at the fixed point
  double rotation_map(const Vec3& x, int branch = 0) const;  // undefined (NaN) on the axis

  // --- extents under each map (normalized units) ------------------------------------------------------
  // A ball, and a beam: the convex hull of balls a and b. Rotation extents are on the branch of the
  // ball's (the beam's start ball's) center; `full` when the axis meets the shape.
  Extent translation_extent(const Ball& ball) const;
  Extent translation_extent(const Ball& a, const Ball& b) const;
  Extent dilation_extent(const Ball& ball) const;
  Extent dilation_extent(const Ball& a, const Ball& b) const;
  Extent rotation_extent(const Ball& ball) const;
  Extent rotation_extent(const Ball& a, const Ball& b) const;

 private:
  SimilarityKind kind_ = SimilarityKind::Identity;
  bool translates_ = false, dilates_ = false, rotates_ = false;
  Vec3 axis_{0.0, 0.0, 1.0}, point_{0.0};
  Vec3 reference_{1.0, 0.0, 0.0}, binormal_{0.0, 1.0, 0.0};  // N and axis x N for the rotation map
  double angle_ = 0.0, step_ = 0.0, log_scale_ = 0.0;
};

// The shape of a row's template R_0: a ball, or a beam (convex hull of two balls).
struct RowTemplate {
  Ball a, b;
  bool is_beam = false;
  static RowTemplate ball(const Ball& ball) { return {ball, ball, false}; }
  static RowTemplate beam(const Ball& a, const Ball& b) { return {a, b, true}; }
};

// The paper's theorem: the indices k in `rows` whose element's extent [t.lo + k, t.hi + k] can overlap
// the query's extent q. Conservative (widened by the slack of the extents).
IndexRange candidate_range(const Extent& query, const Extent& templ, const IndexRange& rows);

// The rotation theorem over all branches: the indices k in `rows` with [t.lo + k, t.hi + k] overlapping
// [q.lo + b P, q.hi + b P] for some integer b, P = period (2 pi / |theta|). Appends one range per branch.
void rotation_candidate_ranges(const Extent& query, const Extent& templ, double period, const IndexRange& rows,
                               IndexRanges& out);

// RangeFinder on a steady row: the indices k in `rows` whose instance S^k(R_0) may meet `query`
// (a superset of the exact answer, usually a few indices). `out` is cleared, then filled normalized.
void steady_row_ranges(const RowMotion& motion, const RowTemplate& templ, const IndexRange& rows, const Ball& query,
                       IndexRanges& out);

}  // namespace steady
