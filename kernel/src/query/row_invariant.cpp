#include "query/row_invariant.hpp"

#include <algorithm>
#include <cmath>

#include "steady/query/interference.hpp"
#include "steady/core/constants.hpp"

namespace steady {
namespace {


// Relative widening of the invariant comparisons: their inputs are within a few ulps of the lattice's
// own evaluation, and the query is already inflated (kQueryInflation) for the rest.
constexpr double kInvariantSlack = 1e-12;

Vec3 radial(const Vec3& x, const Vec3& point, const Vec3& axis) {
  const Vec3 w = x - point;
  return w - glm::dot(w, axis) * axis;
}

// Do the angular intervals [a - ha, a + ha] and [b - hb, b + hb] of angles in [0, pi] overlap, given
// cos/sin of a and b and sin of the half-widths (each half-width in [0, pi/2])? Without inverse trig:
// |a - b| <= ha + hb  <=>  cos(a - b) >= cos(ha + hb) when ha + hb <= pi.
bool angles_overlap(double ca, double sa, double sin_ha, double cb, double sb, double sin_hb) {
  const double cos_ha = std::sqrt(std::max(0.0, 1.0 - sin_ha * sin_ha));
  const double cos_hb = std::sqrt(std::max(0.0, 1.0 - sin_hb * sin_hb));
  const double cos_sum = cos_ha * cos_hb - sin_ha * sin_hb;  // cos(ha + hb), ha + hb <= pi
  const double cos_diff = ca * cb + sa * sb;                 // cos(a - b)
  return cos_diff >= cos_sum - kInvariantSlack;
}

}  // namespace

RowInvariant::RowInvariant(const RowMotion& motion, const Ball& query) : query_(query) {
  const CanonicalForm& c = motion.canonical();
  switch (motion.kind()) {
    case SimilarityKind::Translation:
      type_ = Type::Shadow;
      axis_ = glm::normalize(c.translation);
      q_shadow_ = radial(query.center, Vec3(0.0), axis_);
      break;
    case SimilarityKind::Rotation:
    case SimilarityKind::Screw:
      type_ = Type::AxisDistance;
      axial_too_ = motion.kind() == SimilarityKind::Rotation;
      point_ = c.point;
      axis_ = c.axis;
      q_rho_ = glm::length(radial(query.center, point_, axis_));
      q_axial_ = glm::dot(query.center - point_, axis_);
      break;
    case SimilarityKind::Swirl:
    case SimilarityKind::Dilation: {
      type_ = motion.kind() == SimilarityKind::Swirl ? Type::PolarAngle : Type::Direction;
      point_ = c.point;
      axis_ = c.axis;
      const Vec3 w = query.center - point_;
      q_dist_ = glm::length(w);
      q_contains_point_ = q_dist_ <= query.radius;
      if (!q_contains_point_ && type_ == Type::PolarAngle) {
        q_cos_ = glm::dot(w, axis_) / q_dist_;
        q_sin_ = glm::length(radial(query.center, point_, axis_)) / q_dist_;
      }
      break;
    }
    case SimilarityKind::Identity: type_ = Type::None; break;
  }
}

bool RowInvariant::may_meet(const Ball& t) const {
  const double reach = (query_.radius + t.radius) * (1.0 + kInvariantSlack);
  switch (type_) {
    case Type::None: return true;
    case Type::Shadow: return glm::length(radial(t.center, Vec3(0.0), axis_) - q_shadow_) <= reach;
    case Type::AxisDistance: {
      if (std::abs(glm::length(radial(t.center, point_, axis_)) - q_rho_) > reach) return false;
      return !axial_too_ || std::abs(glm::dot(t.center - point_, axis_) - q_axial_) <= reach;
    }
    case Type::PolarAngle: {
      if (q_contains_point_) return true;
      const Vec3 w = t.center - point_;
      const double d = glm::length(w);
      if (d <= t.radius) return true;
      return angles_overlap(q_cos_, q_sin_, std::min(1.0, query_.radius / q_dist_), glm::dot(w, axis_) / d,
                            glm::length(radial(t.center, point_, axis_)) / d, std::min(1.0, t.radius / d));
    }
    case Type::Direction: {
      // The angle between the query's and the template's directions from F against the sum of the
      // half-angles they subtend (cones about F).
      if (q_contains_point_) return true;
      const Vec3 w = t.center - point_;
      const double d = glm::length(w);
      if (d <= t.radius) return true;
      const Vec3 wq = query_.center - point_;
      const double c = glm::dot(w, wq) / (d * q_dist_);
      const double s = glm::length(glm::cross(w, wq)) / (d * q_dist_);
      return angles_overlap(c, s, std::min(1.0, query_.radius / q_dist_), 1.0, 0.0, std::min(1.0, t.radius / d));
    }
  }
  return true;
}

bool RowInvariant::may_meet(const Ball& a, const Ball& b) const {
  if (type_ == Type::None) return true;
  // First the ball about the axis midpoint that holds the beam: cheap, and enough for most rows.
  const Ball bound{0.5 * (a.center + b.center),
                   0.5 * glm::length(b.center - a.center) + std::max(a.radius, b.radius)};
  if (!may_meet(bound)) return false;
  switch (type_) {
    case Type::None: return true;
    case Type::Shadow: {
      // Across the direction the beam is the 2D hull of its two disks.
      const Vec3 pa = radial(a.center, Vec3(0.0), axis_), pb = radial(b.center, Vec3(0.0), axis_);
      return distance_to_hull(q_shadow_, {pa, a.radius}, {pb, b.radius}) <= query_.radius * (1.0 + kInvariantSlack) +
                                                                                 kInvariantSlack * glm::length(q_shadow_);
    }
    case Type::AxisDistance: {
      // Distance to the axis over the hull: from its shadow's distance to the axis point up to the
      // farther ball.
      const Vec3 ra = radial(a.center, point_, axis_), rb = radial(b.center, point_, axis_);
      const double lo = distance_to_hull(point_, {point_ + ra, a.radius}, {point_ + rb, b.radius});
      const double hi = std::max(glm::length(ra) + a.radius, glm::length(rb) + b.radius);
      const double slack = kInvariantSlack * (hi + q_rho_ + query_.radius);
      if (q_rho_ + query_.radius < lo - slack || q_rho_ - query_.radius > hi + slack) return false;
      if (!axial_too_) return true;
      const double za = glm::dot(a.center - point_, axis_), zb = glm::dot(b.center - point_, axis_);
      return q_axial_ + query_.radius >= std::min(za - a.radius, zb - b.radius) - slack &&
             q_axial_ - query_.radius <= std::max(za + a.radius, zb + b.radius) + slack;
    }
    case Type::PolarAngle: {
      if (q_contains_point_) return true;
      if (bound.radius < 0.25 * glm::length(bound.center - point_)) return true;  // the bound is already tight
      // The polar angles of the two balls, then the hull's: inside the balls' range where the cone
      // {angle <= max} (max <= pi/2) or {angle >= min} (min >= pi/2) is convex; elsewhere bounded by
      // sin(angle) >= (shadow distance to the axis) / (largest distance to F).
      auto polar = [&](const Ball& x, double& lo, double& hi) {
        const Vec3 w = x.center - point_;
        const double d = glm::length(w);
        if (d <= x.radius) {
          lo = 0.0;
          hi = kPi;
          return;
        }
        const double phi = std::atan2(glm::length(radial(x.center, point_, axis_)), glm::dot(w, axis_));
        const double h = std::asin(std::min(1.0, x.radius / d));
        lo = std::max(0.0, phi - h);
        hi = std::min(kPi, phi + h);
      };
      double la, ha, lb, hb;
      polar(a, la, ha);
      polar(b, lb, hb);
      double lo = std::min(la, lb), hi = std::max(ha, hb);
      if (lo < 0.5 * kPi || hi > 0.5 * kPi) {
        const Vec3 ra = radial(a.center, point_, axis_), rb = radial(b.center, point_, axis_);
        const double shadow = std::max(0.0, distance_to_hull(point_, {point_ + ra, a.radius}, {point_ + rb, b.radius}));
        const double far = std::max(glm::length(a.center - point_) + a.radius, glm::length(b.center - point_) + b.radius);
        const double floor = std::asin(std::min(1.0, shadow / far));
        if (lo < 0.5 * kPi) lo = std::min(lo, floor);
        if (hi > 0.5 * kPi) hi = std::max(hi, kPi - floor);
      }
      const double q_phi = std::atan2(q_sin_, q_cos_);
      const double q_h = std::asin(std::min(1.0, query_.radius / q_dist_));
      const double slack = 1e-9;  // radians: atan2 and asin rounding, with headroom
      return q_phi + q_h >= lo - slack && q_phi - q_h <= hi + slack;
    }
    case Type::Direction: return true;  // no cheap bound on the directions of a beam's cone
  }
  return true;
}

}  // namespace steady
