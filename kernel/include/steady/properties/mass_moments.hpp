#pragma once
// The integral properties of a solid as the moments a similarity maps linearly: volume, first moment
// (integral of x), second moment (integral of x x^T), each about the origin of the frame they are expressed
// in, and the area of the outer surface. Properties of a union of solids with disjoint interiors are the sums
// of their moments; properties of a similar copy are the moments mapped by transformed(). Centroid and
// inertia tensor (density 1) follow at the end.
#include "steady/core/similarity.hpp"
#include "steady/core/vec.hpp"

namespace steady {

struct MassMoments {
  double volume = 0.0;   // integral of dV
  Vec3 first{0.0};       // integral of x dV
  Mat3 second{0.0};      // integral of x x^T dV (symmetric)
  double area = 0.0;     // outer surface area (scales like a length squared)

  MassMoments& operator+=(const MassMoments& o);
  MassMoments& operator-=(const MassMoments& o);
  friend MassMoments operator+(MassMoments a, const MassMoments& b) { return a += b; }
  friend MassMoments operator-(MassMoments a, const MassMoments& b) { return a -= b; }
  // Every moment multiplied by `factor` (a count of identical copies, or -1).
  MassMoments scaled(double factor) const;
};

// The moments of the image of the solid under x -> scale * rotation * x + translation.
MassMoments transformed(const MassMoments& m, const SimilarityTransform& t);

// The same solid, its moments taken about `origin` instead of the frame's origin.
MassMoments about(const MassMoments& m, const Vec3& origin);

// Axially symmetric solid about a line through the origin along unit `axis`: from its volume, axial first
// moment (integral of x), axial second moment (integral of x^2) and radial second moment (integral of rho^2).
MassMoments axisymmetric_moments(const Vec3& axis, double volume, double axial_first, double axial_second,
                                 double radial_second, double area);

Vec3 centroid(const MassMoments& m);
// Integral of (x - c)(x - c)^T dV about the centroid c.
Mat3 central_second_moment(const MassMoments& m);
// The inertia tensor about the centroid at density 1: integral of (|r|^2 I - r r^T) dV, r = x - c.
Mat3 central_inertia(const MassMoments& m);

// True when every moment is a finite number.
bool is_finite(const MassMoments& m);

}  // namespace steady
