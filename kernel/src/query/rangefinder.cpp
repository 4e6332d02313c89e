#include "steady/query/rangefinder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "steady/query/interference.hpp"
#include "steady/query/query_tolerance.hpp"

namespace steady {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTwoPi = 6.283185307179586476925286766559;

// A shape whose distance to the rotation axis is below its radius times (1 + this) counts as meeting the
// axis: closer, asin(r / rho) would lose more than kRangeAngleSlack.
constexpr double kAxisContactMargin = 1e-14;

// Below this sine the rotation extent uses tan(asin x) for asin x: wider by x^3 / 6 at most (2% of x at
// 0.35), cheaper than asin, and still an upper bound.
constexpr double kSmallSineForTangentBound = 0.35;

// Widens an extent by an absolute slack plus the relative slack of its own values.
Extent widened(Extent e, double absolute) {
  if (e.full) return e;
  e.lo -= absolute + kRangeRelativeSlack * std::abs(e.lo);
  e.hi += absolute + kRangeRelativeSlack * std::abs(e.hi);
  return e;
}

// floor / ceil of a double clamped into [lo, hi] before the conversion (no overflow, infinities allowed).
std::int64_t clamped_ceil(double x, std::int64_t lo, std::int64_t hi) {
  if (!(x > static_cast<double>(lo))) return lo;  // also NaN: conservative
  if (x > static_cast<double>(hi)) return hi + 1;
  return std::max(lo, static_cast<std::int64_t>(std::ceil(x)));
}
std::int64_t clamped_floor(double x, std::int64_t lo, std::int64_t hi) {
  if (!(x < static_cast<double>(hi))) return hi;  // also NaN
  if (x < static_cast<double>(lo)) return lo - 1;
  return std::min(hi, static_cast<std::int64_t>(std::floor(x)));
}

// A unit vector orthogonal to `a`: the cross product with the basis vector least aligned with it.
Vec3 orthogonal_unit(const Vec3& a) {
  const Vec3 abs_a(std::abs(a.x), std::abs(a.y), std::abs(a.z));
  Vec3 e(0.0);
  e[abs_a.x <= abs_a.y && abs_a.x <= abs_a.z ? 0 : (abs_a.y <= abs_a.z ? 1 : 2)] = 1.0;
  return glm::normalize(glm::cross(a, e));
}

// The component of x - point orthogonal to the unit axis.
Vec3 radial(const Vec3& x, const Vec3& point, const Vec3& axis) {
  const Vec3 w = x - point;
  return w - glm::dot(w, axis) * axis;
}

// Extent of a ball under ln(distance)/step, given its center's distance; the fixed set (F or the line)
// maps to -inf for step > 0 and +inf for step < 0.
Extent log_distance_extent(double distance, double radius, double step) {
  const double far = std::log(distance + radius) / step;
  Extent e;
  if (distance <= radius) {
    e = step > 0.0 ? Extent{-kInf, far, false, 0.0} : Extent{far, kInf, false, 0.0};
  } else {
    const double near = std::log(distance - radius) / step;
    e = {std::min(near, far), std::max(near, far), false, distance - radius};
  }
  return widened(e, kRangeLogSlack / std::abs(step));
}

// Adds ln(nearest distance)/step of a beam (the nearest point may lie on its cone) to the balls' extent.
Extent with_nearest(Extent e, double nearest, double step) {
  e.near = std::min(e.near, std::max(0.0, nearest));
  if (nearest <= 0.0) {
    if (step > 0.0)
      e.lo = -kInf;
    else
      e.hi = kInf;
    return e;
  }
  const double m = std::log(nearest) / step;
  const double slack = kRangeLogSlack / std::abs(step) + kRangeRelativeSlack * std::abs(m);
  e.lo = std::min(e.lo, m - slack);
  e.hi = std::max(e.hi, m + slack);
  return e;
}

}  // namespace

IndexRange intersect(const IndexRange& a, const IndexRange& b) {
  return {std::max(a.lo, b.lo), std::min(a.hi, b.hi)};
}

void IndexRanges::normalize() {
  if (ranges_.size() < 2) return;
  std::sort(ranges_.begin(), ranges_.end(), [](const IndexRange& a, const IndexRange& b) { return a.lo < b.lo; });
  std::size_t w = 0;
  for (std::size_t r = 1; r < ranges_.size(); ++r) {
    if (ranges_[r].lo <= ranges_[w].hi + 1)
      ranges_[w].hi = std::max(ranges_[w].hi, ranges_[r].hi);
    else
      ranges_[++w] = ranges_[r];
  }
  ranges_.resize(w + 1);
}

void IndexRanges::intersect_with(const IndexRange& r) {
  std::size_t w = 0;
  for (const IndexRange& x : ranges_) {
    const IndexRange y = intersect(x, r);
    if (!y.empty()) ranges_[w++] = y;
  }
  ranges_.resize(w);
}

std::int64_t IndexRanges::count() const {
  std::int64_t n = 0;
  for (const IndexRange& r : ranges_) n += r.size();
  return n;
}

bool IndexRanges::contains(std::int64_t k) const {
  for (const IndexRange& r : ranges_)
    if (k >= r.lo && k <= r.hi) return true;
  return false;
}

IndexRange IndexRanges::hull() const {
  if (ranges_.empty()) return {};
  IndexRange h = ranges_.front();
  for (const IndexRange& r : ranges_) {
    h.lo = std::min(h.lo, r.lo);
    h.hi = std::max(h.hi, r.hi);
  }
  return h;
}

// --- NormalizedMap -----------------------------------------------------------------------------------

NormalizedMap NormalizedMap::translation(const Vec3& point, const Vec3& unit_axis, double distance) {
  NormalizedMap m;
  m.type = Type::Translation;
  m.point = point;
  m.axis = unit_axis;
  m.step = distance;
  return m;
}

NormalizedMap NormalizedMap::dilation(const Vec3& fixed_point, double log_scale) {
  NormalizedMap m;
  m.type = Type::Dilation;
  m.point = fixed_point;
  m.step = log_scale;
  return m;
}

NormalizedMap NormalizedMap::axis_dilation(const Vec3& point, const Vec3& unit_axis, double log_scale) {
  NormalizedMap m;
  m.type = Type::AxisDilation;
  m.point = point;
  m.axis = unit_axis;
  m.step = log_scale;
  return m;
}

NormalizedMap NormalizedMap::rotation(const Vec3& point, const Vec3& unit_axis, double angle) {
  NormalizedMap m;
  m.type = Type::Rotation;
  m.point = point;
  m.axis = unit_axis;
  m.step = angle;
  m.reference = orthogonal_unit(unit_axis);
  m.binormal = glm::cross(unit_axis, m.reference);
  return m;
}

double NormalizedMap::period() const { return kTwoPi / step; }

double NormalizedMap::value(const Vec3& x, int branch) const {
  switch (type) {
    case Type::Translation: return glm::dot(x - point, axis) / step;
    case Type::Dilation:
    case Type::AxisDilation: {
      const double r = type == Type::Dilation ? glm::length(x - point) : glm::length(radial(x, point, axis));
      if (r == 0.0) return step > 0.0 ? -kInf : kInf;
      return std::log(r) / step;
    }
    case Type::Rotation: {
      const Vec3 w = x - point;
      const double px = glm::dot(w, reference), py = glm::dot(w, binormal);
      if (px == 0.0 && py == 0.0) return std::numeric_limits<double>::quiet_NaN();
      return std::atan2(py, px) / step + branch * period();
    }
  }
  return 0.0;
}

Extent NormalizedMap::extent(const Ball& ball) const {
  switch (type) {
    case Type::Translation: {
      const double c = value(ball.center), h = ball.radius / std::abs(step);
      return widened({c - h, c + h, false}, 0.0);
    }
    case Type::Dilation: return log_distance_extent(glm::length(ball.center - point), ball.radius, step);
    case Type::AxisDilation:
      return log_distance_extent(glm::length(radial(ball.center, point, axis)), ball.radius, step);
    case Type::Rotation: {
      const Vec3 w = ball.center - point;
      const double px = glm::dot(w, reference), py = glm::dot(w, binormal);
      const double rho = std::sqrt(px * px + py * py);
      if (rho <= ball.radius * (1.0 + kAxisContactMargin) || rho == 0.0) return {0.0, 0.0, true};
      const double c = std::atan2(py, px) / step;
      // Half the angle the ball subtends: asin(x), x = r / rho; for small x the upper bound
      // x / sqrt(1 - x^2) = tan(asin x) is cheaper and off by only x^3 / 6.
      const double x = ball.radius / rho;
      const double half = x < kSmallSineForTangentBound ? x / std::sqrt((1.0 - x) * (1.0 + x)) : std::asin(std::min(1.0, x));
      const double h = half / step;
      return widened({c - h, c + h, false}, kRangeAngleSlack / step);
    }
  }
  return {};
}

Extent NormalizedMap::extent(const Ball& a, const Ball& b) const { return combine(extent(a), extent(b), a, b); }

Extent NormalizedMap::shifted(const Extent& e, double k) const {
  if (e.full) return e;
  Extent s{e.lo + k, e.hi + k, false, e.near};
  // Distances to F or the line scale by e^(step k).
  if (type == Type::Dilation || type == Type::AxisDilation) s.near = e.near * std::exp(step * k);
  return s;
}

bool NormalizedMap::ranges_overlap(const Ball& a, const Ball& b) const {
  const double reach = (a.radius + b.radius) * (1.0 + kRangeRelativeSlack);
  switch (type) {
    case Type::Translation: return std::abs(glm::dot(a.center - b.center, axis)) <= reach + kRangeRelativeSlack * glm::length(a.center - point);
    case Type::Dilation:
      return std::abs(glm::length(a.center - point) - glm::length(b.center - point)) <=
             reach + kRangeRelativeSlack * glm::length(a.center - point);
    case Type::AxisDilation:
      return std::abs(glm::length(radial(a.center, point, axis)) - glm::length(radial(b.center, point, axis))) <=
             reach + kRangeRelativeSlack * glm::length(a.center - point);
    case Type::Rotation: {
      const Extent ea = extent(a), eb = extent(b);
      if (ea.full || eb.full) return true;
      const double P = period();
      const double shift = -P * std::round((0.5 * (eb.lo + eb.hi) - 0.5 * (ea.lo + ea.hi)) / P);
      return eb.lo + shift <= ea.hi && ea.lo <= eb.hi + shift;
    }
  }
  return true;
}

Extent NormalizedMap::combine(const Extent& ea, const Extent& eb, const Ball& a, const Ball& b) const {
  switch (type) {
    case Type::Translation:
      // The extreme points of the hull along the axis lie in one of its balls.
      return {std::min(ea.lo, eb.lo), std::max(ea.hi, eb.hi), false, 0.0};
    case Type::Dilation:
    case Type::AxisDilation: {
      // The farthest point lies in a ball; the nearest may lie on the cone. A lower bound first: every
      // point of the hull is within max(ra, rb) of the segment ab.
      Extent e{std::min(ea.lo, eb.lo), std::max(ea.hi, eb.hi), false, std::min(ea.near, eb.near)};
      Vec3 pa = a.center, pb = b.center;
      if (type == Type::AxisDilation) {
        pa = point + radial(a.center, point, axis);
        pb = point + radial(b.center, point, axis);
      }
      const Vec3 ab = pb - pa;
      const double len2 = glm::dot(ab, ab);
      const double t = len2 > 0.0 ? std::clamp(glm::dot(point - pa, ab) / len2, 0.0, 1.0) : 0.0;
      const double lower = glm::length(point - (pa + t * ab)) - std::max(a.radius, b.radius);
      if (lower >= e.near) return e;
      return with_nearest(e, distance_to_hull(point, {pa, a.radius}, {pb, b.radius}), step);
    }
    case Type::Rotation: {
      if (ea.full || eb.full) return {0.0, 0.0, true, 0.0};
      // b's extent moved by whole periods next to a's (the paper's "proper mapping"): the short way.
      const double P = period();
      const double ca = 0.5 * (ea.lo + ea.hi), cb = 0.5 * (eb.lo + eb.hi);
      const double shift = -P * std::round((cb - ca) / P);
      const Extent e{std::min(ea.lo, eb.lo + shift), std::max(ea.hi, eb.hi + shift), false, 0.0};
      // A convex shape off the axis spans less than half a turn about it; more, and it may meet the axis.
      if (e.hi - e.lo >= 0.5 * P) return {0.0, 0.0, true, 0.0};
      return e;
    }
  }
  return {};
}

// --- RowMotion ---------------------------------------------------------------------------------------

RowMotion RowMotion::from(const Similarity& s) { return from(s.transform()); }

RowMotion RowMotion::from(const SimilarityTransform& t) {
  // The principal logarithm of the map: a winding generator (2 pi about a line) is the identity map.
  const CanonicalForm c = Similarity::from_transform(t).canonical();
  RowMotion m;
  m.kind_ = c.kind;
  m.canonical_ = c;
  switch (c.kind) {
    case SimilarityKind::Identity: break;
    case SimilarityKind::Translation: {
      const double d = glm::length(c.translation);
      m.maps_.push_back(NormalizedMap::translation(Vec3(0.0), c.translation / d, d));
      break;
    }
    case SimilarityKind::Rotation: m.maps_.push_back(NormalizedMap::rotation(c.point, c.axis, c.angle)); break;
    case SimilarityKind::Screw:
      m.maps_.push_back(NormalizedMap::translation(c.point, c.axis, c.distance));
      m.maps_.push_back(NormalizedMap::rotation(c.point, c.axis, c.angle));
      break;
    case SimilarityKind::Dilation: m.maps_.push_back(NormalizedMap::dilation(c.point, std::log(c.scale))); break;
    case SimilarityKind::Swirl:
      m.maps_.push_back(NormalizedMap::dilation(c.point, std::log(c.scale)));
      m.maps_.push_back(NormalizedMap::rotation(c.point, c.axis, c.angle));
      break;
  }
  return m;
}

void RowMotion::add_map(const NormalizedMap& map) {
  if (maps_.size() < kMaxRowMaps) maps_.push_back(map);
}

const NormalizedMap* RowMotion::find(NormalizedMap::Type type) const {
  for (const NormalizedMap& m : maps_)
    if (m.type == type) return &m;
  return nullptr;
}

double RowMotion::angle() const {
  const NormalizedMap* r = find(NormalizedMap::Type::Rotation);
  return r ? r->step : 0.0;
}

// --- theorems ------------------------------------------------------------------------------------------

IndexRange candidate_range(const Extent& query, const Extent& templ, const IndexRange& rows) {
  if (rows.empty()) return rows;
  // Element k covers [t.lo + k, t.hi + k]; it overlaps [q.lo, q.hi] iff q.lo - t.hi <= k <= q.hi - t.lo.
  return {clamped_ceil(query.lo - templ.hi, rows.lo, rows.hi), clamped_floor(query.hi - templ.lo, rows.lo, rows.hi)};
}

void rotation_candidate_ranges(const Extent& query, const Extent& templ, double period, const IndexRange& rows,
                               IndexRanges& out) {
  if (rows.empty()) return;
  if (query.full || templ.full) {
    out.add(rows);
    return;
  }
  const double d_lo = query.lo - templ.hi, d_hi = query.hi - templ.lo;
  // Windows [d_lo + b P, d_hi + b P] as wide as the period cover every index.
  if (d_hi - d_lo >= period) {
    out.add(rows);
    return;
  }
  // Branches whose window meets [rows.lo, rows.hi]: one range per wrap of the row.
  const double b_first = std::ceil((static_cast<double>(rows.lo) - d_hi) / period);
  const double b_last = std::floor((static_cast<double>(rows.hi) - d_lo) / period);
  for (double b = b_first; b <= b_last; b += 1.0) {
    const double shift = b * period;
    out.add({clamped_ceil(d_lo + shift, rows.lo, rows.hi), clamped_floor(d_hi + shift, rows.lo, rows.hi)});
  }
}

QueryExtents query_extents(const RowMotion& motion, const Ball& query) {
  QueryExtents q;
  q.query = query;
  for (std::size_t m = 0; m < motion.maps().size(); ++m) q.extents[m] = motion.maps()[m].extent(query);
  return q;
}

void steady_row_ranges(const RowMotion& motion, const QueryExtents& query, const Extent* templ_extents,
                       const IndexRange& rows, IndexRanges& out) {
  out.clear();
  if (rows.empty()) return;
  // The single-valued maps first (cheap, and they bound the wraps the rotation map has to visit).
  IndexRange range = rows;
  const auto& maps = motion.maps();
  std::size_t rotation = maps.size();
  for (std::size_t m = 0; m < maps.size(); ++m) {
    if (maps[m].type == NormalizedMap::Type::Rotation) {
      rotation = m;
      continue;
    }
    range = candidate_range(query.extents[m], templ_extents[m], range);
    if (range.empty()) return;
  }
  if (rotation == maps.size()) {
    out.add(range);
    return;
  }
  rotation_candidate_ranges(query.extents[rotation], templ_extents[rotation], maps[rotation].period(), range, out);
  out.normalize();
}

void steady_row_ranges(const RowMotion& motion, const QueryExtents& query, const RowTemplate& templ,
                       const IndexRange& rows, IndexRanges& out) {
  out.clear();
  if (rows.empty()) return;
  if (motion.kind() == SimilarityKind::Identity && motion.identity_tests_template()) {
    // Every instance is the template itself.
    const double d = templ.is_beam ? distance_to_hull(query.query.center, templ.a, templ.b)
                                   : distance_to_ball(query.query.center, templ.a);
    if (d <= query.query.radius) out.add(rows);
    return;
  }
  // The single-valued maps first (cheap, and they bound the wraps the rotation map has to visit); the
  // rotation extent only when candidates remain.
  IndexRange range = rows;
  const auto& maps = motion.maps();
  std::size_t rotation = maps.size();
  for (std::size_t m = 0; m < maps.size(); ++m) {
    if (maps[m].type == NormalizedMap::Type::Rotation) {
      rotation = m;
      continue;
    }
    const Extent t = templ.is_beam ? maps[m].extent(templ.a, templ.b) : maps[m].extent(templ.a);
    range = candidate_range(query.extents[m], t, range);
    if (range.empty()) return;
  }
  if (rotation == maps.size()) {
    out.add(range);
    return;
  }
  const NormalizedMap& r = maps[rotation];
  const Extent t = templ.is_beam ? r.extent(templ.a, templ.b) : r.extent(templ.a);
  rotation_candidate_ranges(query.extents[rotation], t, r.period(), range, out);
  out.normalize();
}

void steady_row_ranges(const RowMotion& motion, const RowTemplate& templ, const IndexRange& rows, const Ball& query,
                       IndexRanges& out) {
  steady_row_ranges(motion, query_extents(motion, query), templ, rows, out);
}

}  // namespace steady
