#include "steady/rangefinder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "steady/interference.hpp"
#include "steady/query_tolerance.hpp"
#include "steady/tolerance.hpp"

namespace steady {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTwoPi = 6.283185307179586476925286766559;

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

// --- RowMotion ---------------------------------------------------------------------------------------

RowMotion RowMotion::from(const Similarity& s) { return from(s.transform()); }

RowMotion RowMotion::from(const SimilarityTransform& t) {
  // The principal logarithm of the map: a winding generator (2 pi about a line) is the identity map.
  const CanonicalForm c = Similarity::from_transform(t).canonical();
  RowMotion m;
  m.kind_ = c.kind;
  switch (c.kind) {
    case SimilarityKind::Identity: break;
    case SimilarityKind::Translation: {
      m.translates_ = true;
      m.step_ = glm::length(c.translation);
      m.axis_ = c.translation / m.step_;
      m.point_ = Vec3(0.0);
      break;
    }
    case SimilarityKind::Rotation:
    case SimilarityKind::Screw:
      m.rotates_ = true;
      m.translates_ = c.kind == SimilarityKind::Screw;
      m.axis_ = c.axis;
      m.point_ = c.point;
      m.angle_ = c.angle;
      m.step_ = c.distance;
      break;
    case SimilarityKind::Dilation:
      m.dilates_ = true;
      m.point_ = c.point;
      m.log_scale_ = std::log(c.scale);
      break;
    case SimilarityKind::Swirl:
      m.dilates_ = true;
      m.rotates_ = true;
      m.axis_ = c.axis;
      m.point_ = c.point;
      m.angle_ = c.angle;
      m.log_scale_ = std::log(c.scale);
      break;
  }
  if (m.rotates_) {
    // Reference direction N orthogonal to the axis: the basis vector least aligned with it.
    const Vec3& a = m.axis_;
    Vec3 e(0.0);
    const Vec3 abs_a(std::abs(a.x), std::abs(a.y), std::abs(a.z));
    e[abs_a.x <= abs_a.y && abs_a.x <= abs_a.z ? 0 : (abs_a.y <= abs_a.z ? 1 : 2)] = 1.0;
    m.reference_ = glm::normalize(glm::cross(a, e));
    m.binormal_ = glm::cross(a, m.reference_);
  }
  return m;
}

double RowMotion::translation_map(const Vec3& x) const { return glm::dot(x - point_, axis_) / step_; }

double RowMotion::dilation_map(const Vec3& x) const {
  const double r = glm::length(x - point_);
  if (r == 0.0) return log_scale_ > 0.0 ? -kInf : kInf;
  return std::log(r) / log_scale_;
}

double RowMotion::rotation_map(const Vec3& x, int branch) const {
  const Vec3 w = x - point_;
  const double px = glm::dot(w, reference_), py = glm::dot(w, binormal_);
  if (px == 0.0 && py == 0.0) return std::numeric_limits<double>::quiet_NaN();
  return std::atan2(py, px) / angle_ + branch * (kTwoPi / angle_);
}

Extent RowMotion::translation_extent(const Ball& ball) const {
  const double c = translation_map(ball.center), h = ball.radius / std::abs(step_);
  return widened({c - h, c + h, false}, 0.0);
}

Extent RowMotion::translation_extent(const Ball& a, const Ball& b) const {
  // The extreme points of the hull along the axis lie in one of its balls.
  const Extent ea = translation_extent(a), eb = translation_extent(b);
  return {std::min(ea.lo, eb.lo), std::max(ea.hi, eb.hi), false};
}

Extent RowMotion::dilation_extent(const Ball& ball) const {
  const double rho = glm::length(ball.center - point_);
  const double far = std::log(rho + ball.radius) / log_scale_;
  Extent e;
  if (rho <= ball.radius) {
    // The fixed point is inside: its map value is -inf (s > 1) or +inf (s < 1).
    e = log_scale_ > 0.0 ? Extent{-kInf, far, false} : Extent{far, kInf, false};
  } else {
    const double near = std::log(rho - ball.radius) / log_scale_;
    e = {std::min(near, far), std::max(near, far), false};
  }
  return widened(e, kRangeLogSlack / std::abs(log_scale_));
}

Extent RowMotion::dilation_extent(const Ball& a, const Ball& b) const {
  // The farthest point from F lies in a ball; the nearest may lie on the cone: add ln(distance to hull).
  const Extent ea = dilation_extent(a), eb = dilation_extent(b);
  Extent e{std::min(ea.lo, eb.lo), std::max(ea.hi, eb.hi), false};
  const double f = distance_to_hull(point_, a, b);
  if (f <= 0.0) {
    if (log_scale_ > 0.0)
      e.lo = -kInf;
    else
      e.hi = kInf;
  } else {
    const double m = std::log(f) / log_scale_;
    const double slack = kRangeLogSlack / std::abs(log_scale_) + kRangeRelativeSlack * std::abs(m);
    e.lo = std::min(e.lo, m - slack);
    e.hi = std::max(e.hi, m + slack);
  }
  return e;
}

Extent RowMotion::rotation_extent(const Ball& ball) const {
  const Vec3 w = ball.center - point_;
  const double px = glm::dot(w, reference_), py = glm::dot(w, binormal_);
  const double rho = std::hypot(px, py);
  // The axis meets the ball (or nearly: asin would lose its accuracy): every angle.
  if (rho <= ball.radius * (1.0 + 1e-14) || rho == 0.0) return {0.0, 0.0, true};
  const double c = std::atan2(py, px) / angle_;
  const double h = std::asin(std::min(1.0, ball.radius / rho)) / angle_;
  return widened({c - h, c + h, false}, kRangeAngleSlack / angle_);
}

Extent RowMotion::rotation_extent(const Ball& a, const Ball& b) const {
  // The beam's shadow along the axis is the 2D hull of the two disks; the axis meets the beam exactly
  // when that shadow contains the axis point.
  const Vec3 wa = a.center - point_, wb = b.center - point_;
  const Vec3 pa = a.center - glm::dot(wa, axis_) * axis_, pb = b.center - glm::dot(wb, axis_) * axis_;
  const double shadow_gap = distance_to_hull(point_, {pa, a.radius}, {pb, b.radius});
  const double scale = glm::length(pa - point_) + glm::length(pb - point_) + a.radius + b.radius;
  if (shadow_gap <= 1e-14 * scale) return {0.0, 0.0, true};
  const Extent ea = rotation_extent(a), eb_alone = rotation_extent(b);
  if (ea.full || eb_alone.full) return {0.0, 0.0, true};
  // b's center mapped relative to a's (the paper's "proper mapping"), so both ends share a branch lift.
  const double ax = glm::dot(wa, reference_), ay = glm::dot(wa, binormal_);
  const double bx = glm::dot(wb, reference_), by = glm::dot(wb, binormal_);
  const double relative = std::atan2(ax * by - ay * bx, ax * bx + ay * by);
  const double ca = 0.5 * (ea.lo + ea.hi);
  const double cb = ca + relative / angle_;
  const double hb = 0.5 * (eb_alone.hi - eb_alone.lo);
  return {std::min(ea.lo, cb - hb), std::max(ea.hi, cb + hb), false};
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

void steady_row_ranges(const RowMotion& motion, const RowTemplate& templ, const IndexRange& rows, const Ball& query,
                       IndexRanges& out) {
  out.clear();
  if (rows.empty()) return;
  IndexRange range = rows;
  switch (motion.kind()) {
    case SimilarityKind::Identity: {
      // Every instance is the template itself.
      const double d = templ.is_beam ? distance_to_hull(query.center, templ.a, templ.b)
                                     : distance_to_ball(query.center, templ.a);
      if (d <= query.radius) out.add(range);
      return;
    }
    case SimilarityKind::Translation:
    case SimilarityKind::Screw: {
      const Extent t = templ.is_beam ? motion.translation_extent(templ.a, templ.b) : motion.translation_extent(templ.a);
      range = candidate_range(motion.translation_extent(query), t, range);
      break;
    }
    case SimilarityKind::Dilation:
    case SimilarityKind::Swirl: {
      const Extent t = templ.is_beam ? motion.dilation_extent(templ.a, templ.b) : motion.dilation_extent(templ.a);
      range = candidate_range(motion.dilation_extent(query), t, range);
      break;
    }
    case SimilarityKind::Rotation: break;
  }
  if (range.empty()) return;
  if (!motion.rotates()) {
    out.add(range);
    return;
  }
  const Extent t = templ.is_beam ? motion.rotation_extent(templ.a, templ.b) : motion.rotation_extent(templ.a);
  rotation_candidate_ranges(motion.rotation_extent(query), t, kTwoPi / motion.angle(), range, out);
  out.normalize();
}

}  // namespace steady
