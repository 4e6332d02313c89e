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
// One more map, not in the paper: for a dilation (or a swirl) about F, the distance to any line A through
// F (for a swirl: its axis) scales by s too, so M(x) = ln dist(x, A) / ln s is normalized. It is what
// makes a cylindrical lattice's radial direction invariant under its rotation and its axial translation
// (see LatticeQuery: the O(1) path then applies where the paper only had O(u)).
//
// The rotation map is multi-valued: the query's extent exists in every branch, sq + b P, eq + b P with
// P = 2 pi / |theta|. Instead of the paper's two-branch rule (which misses the branch -1 case of the
// digest's counter-example and rows that wrap) every branch b whose window meets the row's index range
// is evaluated, so the answer is a list of disjoint ranges, one per wrap at most.
//
// Conservative by construction: extents are widened by a slack covering the rounding of logarithms,
// angles and divisions (query_tolerance.hpp); callers inflate the query ball to cover the rounding of
// the elements' own evaluation.
#include <array>
#include <cstdint>
#include <vector>

#include "steady/core/ball.hpp"
#include "steady/core/similarity.hpp"

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
// shape); `full` marks a rotation extent that covers every angle (the axis meets the shape). `near` is,
// for the two dilation maps, the shape's smallest distance to the fixed point or line (0 when it
// contains it): a beam's extent then needs its cone's nearest point only when that comes closer.
struct Extent {
  double lo = 0.0, hi = 0.0;
  bool full = false;
  double near = 0.0;
};

// A motion carries at most this many maps: its canonical two, plus the alternatives the lattice query
// tries (one distance-to-a-line map per other direction, three dual projections for a translation).
constexpr std::size_t kMaxRowMaps = 6;

// One normalized map of a row motion.
struct NormalizedMap {
  enum class Type { Translation, Dilation, AxisDilation, Rotation };
  Type type = Type::Translation;
  Vec3 point{0.0};                 // P on the axis, or the fixed point F
  Vec3 axis{0.0, 0.0, 1.0};        // unit (translation direction, rotation axis, line of AxisDilation)
  Vec3 reference{1.0, 0.0, 0.0};   // rotation: N, orthogonal to the axis
  Vec3 binormal{0.0, 1.0, 0.0};    // rotation: axis x N
  double step = 1.0;               // per step: distance (T), ln s (D, AxisDilation), angle in (0, pi] (R)

  static NormalizedMap translation(const Vec3& point, const Vec3& unit_axis, double distance);
  static NormalizedMap dilation(const Vec3& fixed_point, double log_scale);
  static NormalizedMap axis_dilation(const Vec3& point, const Vec3& unit_axis, double log_scale);
  static NormalizedMap rotation(const Vec3& point, const Vec3& unit_axis, double angle);

  // M(x); the rotation value is on branch `branch` (NaN on the axis); dilations give +-inf at F / on A.
  double value(const Vec3& x, int branch = 0) const;
  // Extent of a ball, and of a beam (the convex hull of balls a and b). Rotation extents are lifted
  // around the branch-0 value of the (start) ball's center.
  Extent extent(const Ball& ball) const;
  Extent extent(const Ball& a, const Ball& b) const;
  // A beam's extent from its two balls' extents (ea of a, eb of b; eb may be the extent of b's
  // preimage shifted by some k, any lift): the balls' union joined the short way for a rotation (full
  // when that spans half a turn or more: the hull can then reach the axis), the union for a
  // translation, and for the dilations the union extended to the cone's nearest point when that comes
  // closer to F (or the line) than both balls. Equal to extent(a, b) up to the rotation case's
  // conservative "full".
  Extent combine(const Extent& ea, const Extent& eb, const Ball& a, const Ball& b) const;
  // The extent of S^k(shape) from the shape's extent.
  Extent shifted(const Extent& e, double k) const;
  // Do the value ranges of two balls overlap? (Closed form in distances and angles, no logarithm; the
  // test a map that other motions leave unchanged gives for "same index".)
  bool ranges_overlap(const Ball& a, const Ball& b) const;
  // The rotation period 2 pi / theta in map units (rotation maps only).
  double period() const;
};

// The canonical decomposition of a row's incremental similarity S with the normalized maps of its
// primitives. Built from the group element of S (its principal logarithm), so only the map S matters.
class RowMotion {
 public:
  static RowMotion from(const Similarity& s);
  static RowMotion from(const SimilarityTransform& t);

  SimilarityKind kind() const { return kind_; }
  const CanonicalForm& canonical() const { return canonical_; }
  bool translates() const { return find(NormalizedMap::Type::Translation) != nullptr; }
  bool dilates() const { return find(NormalizedMap::Type::Dilation) != nullptr; }
  bool rotates() const { return find(NormalizedMap::Type::Rotation) != nullptr; }
  double angle() const;  // theta per step in (0, pi] of the rotation map

  // The maps RangeFinder intersects. Dropping maps keeps the ranges valid (looser); a non-identity
  // motion with no map left yields the full range.
  const std::vector<NormalizedMap>& maps() const { return maps_; }
  const NormalizedMap* find(NormalizedMap::Type type) const;
  // Adds a map (ignored beyond kMaxRowMaps: fewer maps only loosen the ranges).
  void add_map(const NormalizedMap& map);
  void remove_map(std::size_t index) { maps_.erase(maps_.begin() + static_cast<std::ptrdiff_t>(index)); }
  // For the identity every instance is the template, so RangeFinder tests the template itself. That is
  // only right when the template is the row's own element 0; paths that let one template stand in for
  // several rows (O(u), O(1)) turn it off and get the full range instead.
  bool identity_tests_template() const { return identity_tests_template_; }
  void set_identity_tests_template(bool on) { identity_tests_template_ = on; }

  // The paper's maps of this motion (convenience for tests; the map must exist).
  double translation_map(const Vec3& x) const { return find(NormalizedMap::Type::Translation)->value(x); }
  double dilation_map(const Vec3& x) const { return find(NormalizedMap::Type::Dilation)->value(x); }
  double rotation_map(const Vec3& x, int branch = 0) const {
    return find(NormalizedMap::Type::Rotation)->value(x, branch);
  }
  Extent translation_extent(const Ball& b) const { return find(NormalizedMap::Type::Translation)->extent(b); }
  Extent translation_extent(const Ball& a, const Ball& b) const {
    return find(NormalizedMap::Type::Translation)->extent(a, b);
  }
  Extent dilation_extent(const Ball& b) const { return find(NormalizedMap::Type::Dilation)->extent(b); }
  Extent dilation_extent(const Ball& a, const Ball& b) const {
    return find(NormalizedMap::Type::Dilation)->extent(a, b);
  }
  Extent rotation_extent(const Ball& b) const { return find(NormalizedMap::Type::Rotation)->extent(b); }
  Extent rotation_extent(const Ball& a, const Ball& b) const {
    return find(NormalizedMap::Type::Rotation)->extent(a, b);
  }

 private:
  SimilarityKind kind_ = SimilarityKind::Identity;
  CanonicalForm canonical_;
  std::vector<NormalizedMap> maps_;
  bool identity_tests_template_ = true;
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

// The query's extents under a motion's maps, computed once and reused for every row of that motion
// (a lattice query runs RangeFinder on up to u v rows with one query ball).
struct QueryExtents {
  Ball query;
  std::array<Extent, kMaxRowMaps> extents;  // one per map of the motion, in order
};
QueryExtents query_extents(const RowMotion& motion, const Ball& query);
void steady_row_ranges(const RowMotion& motion, const QueryExtents& query, const RowTemplate& templ,
                       const IndexRange& rows, IndexRanges& out);
// The same from the template's extents (one per map of the motion, e.g. combined from cached ball
// extents); the motion must not be the identity (that case needs the template's geometry).
void steady_row_ranges(const RowMotion& motion, const QueryExtents& query, const Extent* templ_extents,
                       const IndexRange& rows, IndexRanges& out);

}  // namespace steady
