#pragma once
// Early rejection of a whole steady row (beyond the paper, which lists it as future work): a function of
// space the row's motion S leaves unchanged takes on every instance S^k(R_0) the same values as on the
// template R_0, so a query ball whose values miss the template's meets no instance at all, whatever k.
// RangeFinder's maps only bound the index along the motion; these bound the directions across it,
// where the paper's false positives come from (a query inside a row's slab, shell or wedge but far
// from the row).
//     translation        the position across the direction (the row's shadow along it)
//     rotation, screw    the distance to the axis (and, for a pure rotation, the position along it)
//     swirl              the angle between the axis and the direction from the fixed point (a cone)
//     dilation           the direction from the fixed point
// The tests are closed-form and conservative (an answer "may meet" is never wrong; "misses" is exact up
// to the query's inflation).
#include "steady/core/ball.hpp"
#include "steady/query/rangefinder.hpp"

namespace steady {

class RowInvariant {
 public:
  enum class Type { None, Shadow, AxisDistance, PolarAngle, Direction };

  // The invariant of a motion, prepared for one query ball (done once per query, used for every row).
  RowInvariant(const RowMotion& motion, const Ball& query);

  Type type() const { return type_; }
  // False only when no instance of the row with this template can meet the query.
  bool may_meet(const Ball& templ) const;
  bool may_meet(const Ball& a, const Ball& b) const;  // a beam: the convex hull of two balls

 private:
  Type type_ = Type::None;
  bool axial_too_ = false;  // pure rotation: the position along the axis is kept as well
  Vec3 point_{0.0}, axis_{0.0, 0.0, 1.0};
  Ball query_;
  // Prepared query values.
  Vec3 q_shadow_{0.0};
  double q_rho_ = 0.0, q_axial_ = 0.0;
  double q_cos_ = 1.0, q_sin_ = 0.0, q_dist_ = 0.0;  // polar angle of the query center, its distance to F
  bool q_contains_point_ = false;                    // the query contains F
};

}  // namespace steady
