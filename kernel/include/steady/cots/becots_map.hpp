#pragma once
// The BeCOTS (bent COTS) map of Kurzeja's dissertation, chapter 4 (docs/cots.md, spec constructive-lattice-geometry.md):
// the 3D field S(x,y) = Rotation(x w_u + y w_v, F, T) o Dilation(m_u^x m_v^y, F), one apex F and one axis T shared
// by both factors (so they commute and every tile is similar to every other), applied to the corner A:
//     M(x,y) = F + m_u^x m_v^y Rot_T(x w_u + y w_v)(A - F),   M(0,0) = A, M(0,1) = B, M(1,1) = C, M(1,0) = D.
// The range lies on the cone with apex F and axis T.
//
// Representation, chosen so that nothing divides by m - 1 (the dissertation's F = F' - h T, h = AC.T/(m-1)):
// the map splits along T into its shadow on the plane through A across T, which is a planar COTS map (the
// dissertation's Project), and its height above that plane,
//     height(x,y) = phi(x ln m_u + y ln m_v) (x hu + y hv),   hu = (D - A).T / phi(ln m_u),   hv = (B - A).T / phi(ln m_v),
// with phi(s) = (e^s - 1)/s. As |CD|/|AB| and |BC|/|AD| approach 1 the apex runs to infinity along the axis and the
// same expression tends to a pair of coaxial screws (a range on a cylinder), with no division by a vanishing
// dilation. |AB| = |CD| alone is an ordinary BeCOTS map whose U is a pure rotation. |AB| = |CD| together with
// |AD| = |BC| off a plane is refused: a one-parameter family of coaxial screw fields, on cylinders of different
// axes, passes through such corners (the axis condition below has no unique solution).
//
// The axis is the direction orthogonal to unit(DC) - unit(AB) and to unit(BC) - unit(AD) (the rotation about T that
// turns AB's direction into DC's, and AD's into BC's). Coplanar corners give the planar COTS map in their plane
// (the axis is the plane's normal, any shape the planar map accepts, parallelograms included). Refused, with
// InvalidInput naming the corners: NaN or infinite corners, adjacent corners that coincide, collinear corners,
// non-coplanar corners whose axis is undetermined (a one-parameter family of fields passes through them), and
// ranges that collapse to a curve.
#include <optional>
#include <vector>

#include "steady/core/similarity.hpp"
#include "steady/core/vec.hpp"
#include "steady/cots/cots_map.hpp"

namespace steady {

// Relative volume |det(B-A, C-A, D-A)| / diameter^3 at or below which four corners count as coplanar (their
// heights above the plane are then exactly 0). 1e-12 is four digits above the rounding of the determinant.
constexpr double kBecotsCoplanarTolerance = 1e-12;

// |(unit(DC) - unit(AB)) x (unit(BC) - unit(AD))| (at most 4) at or below which the axis of non-coplanar corners
// counts as undetermined. The axis' direction error is ~1e-16 divided by it: below 1e-9 it is no longer a direction.
constexpr double kBecotsAxisTolerance = 1e-9;

// Distance, relative to the corners' diameter plus |Q - A|, within which a point counts as lying on the range
// (BecotsMap::inverse): evaluations of the map are accurate to ~1e-14 of that size.
constexpr double kBecotsSurfaceTolerance = 1e-9;

class BecotsMap {
 public:
  using Complex = std::complex<double>;

  // The field through M(0,0) = a, M(0,1) = b, M(1,1) = c, M(1,0) = d. The axis points so that the map with principal
  // angles turns counterclockwise about it (positive orientation); branch_u and branch_v add whole turns about it.
  BecotsMap(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int branch_u = 0, int branch_v = 0);
  // The field of apex `apex`, axis `axis` (any length), log multipliers log_u = ln m_u + i w_u (x) and
  // log_v = ln m_v + i w_v (y), applied to the corner a.
  static BecotsMap from_field(const Vec3& apex, const Vec3& axis, const Vec3& a, Complex log_u, Complex log_v);

  Vec3 map(double x, double y) const;
  Vec3 map(const Vec2& uv) const { return map(uv.x, uv.y); }

  // Every pre-image of q in the box (default [0,1]^2) whose image lies within `tolerance` (relative, see
  // kBecotsSurfaceTolerance) of q; empty for points off the range.
  std::vector<CotsPreimage> inverse(const Vec3& q, const ParameterBox& box = {},
                                    double tolerance = kBecotsSurfaceTolerance) const;
  std::vector<std::array<int, 2>> tiles_of(const Vec3& q, int nu, int nv) const;

  // The 3D similarity S(x,y) (M(x,y) = S(x,y)(A)); U = S(1,0), V = S(0,1); tile (i,j) = S(i/nu, j/nv) tile (0,0).
  Similarity field(double x, double y) const;
  Similarity u_similarity() const { return field(1.0, 0.0); }
  Similarity v_similarity() const { return field(0.0, 1.0); }
  Similarity tile_similarity(int i, int j, int nu, int nv) const;

  // Area of the range on its cone (overlapping parts counted as often as they are covered), in closed form: the
  // bent sheet keeps the area of its unbent COTS map.
  double area() const;
  double tile_area(int i, int j, int nu, int nv) const;

  // Raise: the same apex, axis, multipliers and angles, with A moved by z along the axis.
  BecotsMap raised(double z) const;
  // Project: the planar COTS map in the plane through the apex across the axis (the raise that brings A there).
  BecotsMap projected() const;
  // The sheet of this map unrolled into the plane through its apex and A (geodesic distances kept).
  BecotsMap unbent() const;
  // The unrolled sheet rolled onto the right circular cone of half-angle beta in (0, pi) about the apex, tangent to
  // the sheet's plane along the line FA (beta = pi/2 leaves the sheet flat).
  BecotsMap bent(double beta) const;
  // The angle between the axis and FA: the cone's half-angle (pi/2 for a flat map).
  double bend_angle() const;
  // (A - F).T: how far A lies above the plane through the apex across the axis (0 for a flat map).
  double height() const;
  // The unit normal of the range at A, dM/dx x dM/dy normalized (so it follows the map's orientation). It lies in
  // the plane through A and the axis (the range is a surface of revolution about it), so moving A along it moves A
  // across the cones about the apex: the normal-offset layers of a stack (6.3 (b)).
  Vec3 normal() const;

  Vec3 a() const { return a_; }
  Vec3 b() const { return b_; }
  Vec3 c() const { return c_; }
  Vec3 d() const { return d_; }
  const Vec3& axis() const { return axis_; }
  std::optional<Vec3> apex() const;
  Complex log_u() const { return shadow_.log_u(); }
  Complex log_v() const { return shadow_.log_v(); }
  bool is_flat() const { return flat_; }
  // The map's shadow along the axis on the plane through A, in the frame (A, plane_x, plane_y).
  const CotsMap& shadow() const { return shadow_; }
  const Vec3& plane_x() const { return plane_x_; }
  const Vec3& plane_y() const { return plane_y_; }

 private:
  friend class BecotsRangeFinder;
  BecotsMap() = default;
  void set_axis(const Vec3& axis);
  void finish();
  Vec3 embed(const Vec2& p) const { return plane_x_ * p.x + plane_y_ * p.y; }
  Vec2 shadow_of(const Vec3& q) const;
  // (q' - f') / (a' - f') for the shadows q', a' and the apex's f': its modulus is the ratio of the distances to the
  // axis, its argument the azimuth from A's (formed without f').
  Complex shadow_ratio(const Vec3& q) const;
  std::vector<CotsPreimage> solve_cone(const Vec3& q, const ParameterBox& box) const;

  Vec3 a_{0.0}, b_{0.0}, c_{0.0}, d_{0.0};
  Vec3 axis_{0.0, 0.0, 1.0}, plane_x_{1.0, 0.0, 0.0}, plane_y_{0.0, 1.0, 0.0};
  CotsMap shadow_;          // the planar map of the shadows, corner a at the origin
  double hu_ = 0.0, hv_ = 0.0;  // height rates: (D - A).T / phi(ln m_u), (B - A).T / phi(ln m_v)
  bool flat_ = true;
  // Derived for the inverse, the area and the range finder (whenever there is an apex): A - F = radial + height_ T,
  // its length, and the well-scaled 2 x 2 system [pu pv; qu qv] (x, y) = (radial log distance, arc length).
  Complex radial_{0.0};  // the shadow of A - F in the plane frame (finite unless the shadow is a parallelogram)
  double height_ = 0.0;      // (A - F).T
  double inv_length_ = 0.0;  // 1/|A - F|
  Vec3 radial_dir_{0.0};     // (A - F)/|A - F|
  double pu_ = 0.0, pv_ = 0.0, qu_ = 0.0, qv_ = 0.0;
  double diameter_ = 0.0;
};

}  // namespace steady
