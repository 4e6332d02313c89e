#pragma once
// The planar Corner-Operated Tran-Similar (COTS) map of Rossignac (docs/cots.md, spec cots-maps.md).
//
// Four corners a, b, c, d set the map M of the unit square with M(0,0) = a, M(0,1) = b, M(1,1) = c,
// M(1,0) = d (x runs a -> d, y runs a -> b). In complex form M(x,y) = f + exp(x Lu + y Lv) (a - f): U = SIM(a,b,d,c)
// (a -> d, b -> c) and V = SIM(a,d,b,c) (a -> b, d -> c) are two spirals about one fixed point f (the four-point
// similarity centre), so they commute and every tile of a regular grid is a similar copy of every other.
//
// The map is evaluated in the form that needs no f,
//     M(x,y) = a + phi(x Lu + y Lv) (x gu + y gv),   phi(z) = (e^z - 1)/z,   gu = (d - a)/phi(Lu), gv = (b - a)/phi(Lv),
// where gu = Lu (a - f) and gv = Lv (a - f) stay finite as the corners approach a parallelogram (f runs to
// infinity). On an exact parallelogram Lu = Lv = 0 and the same expression is the affine map a + x(d-a) + y(b-a)
// (the paper's ACOTS): the parallelogram is not a separate code path of the evaluation, only of the inverse.
//
// What is refused (InvalidInput naming the corners): NaN or infinite corners, adjacent corners that coincide
// (|ab|, |bc|, |cd| or |da| = 0), and ranges that collapse to a curve (the isocurves' crossing angle is 0 or pi:
// collinear parallelograms, and spirals whose Lu and Lv are real multiples of each other). Folded (self-crossing)
// corner quads are valid: the COTS map never folds (its Jacobian keeps one sign, the sign of the orientation).
#include <array>
#include <complex>
#include <optional>
#include <vector>

#include "steady/core/similarity2d.hpp"
#include "steady/core/vec.hpp"

namespace steady {

// Relative distance (to the corners' diameter) at or below which two adjacent corners count as one point: the
// map's multiplier |cd|/|ab| would then be 0 or infinite. 1e-12 leaves four digits above double rounding.
constexpr double kCotsCoincidenceTolerance = 1e-12;

// |sin| of the isocurves' crossing angle at or below which the range counts as collapsed to a curve: the inverse
// divides by it, so 1e-10 still leaves ~6 significant digits of (x, y).
constexpr double kCotsCollapseTolerance = 1e-10;

// How far outside the parameter box a pre-image may fall and still count (it is then clamped onto the box):
// the closed-form inverse is accurate to ~1e-14 on well-shaped maps, so corners and borders are found.
constexpr double kCotsParameterTolerance = 1e-10;

// Largest |branch| accepted for the angle windings of U and V: 1e5 turns (kMaxAngle allows 1.6e5).
constexpr int kCotsMaxBranch = 100000;

// A pre-image (x, y) of a point, and the branch k of the logarithm it was found on (the angle about the fixed point
// was measured as arg + 2 pi k). Several pre-images of one point mean the range overlaps itself there.
struct CotsPreimage {
  Vec2 uv{0.0};
  int branch = 0;
};

// A rectangle of the parameter plane; [0,1]^2 is the map's own domain, larger boxes extend the map beyond R.
struct ParameterBox {
  double x0 = 0.0, x1 = 1.0, y0 = 0.0, y1 = 1.0;
};

class CotsMap {
 public:
  using Complex = std::complex<double>;

  // The map with M(0,0) = a, M(0,1) = b, M(1,1) = c, M(1,0) = d. branch_u and branch_v add whole turns to the
  // angles of U and V (principal angles in (-pi, pi] otherwise): maps that wind more than a half turn.
  CotsMap(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, int branch_u = 0, int branch_v = 0);
  // The map f + exp(x log_u + y log_v)(a - f), any windings (the corners follow from it).
  static CotsMap from_spiral(const Vec2& a, const Vec2& center, Complex log_u, Complex log_v);

  Vec2 map(double x, double y) const;
  Vec2 map(const Vec2& uv) const { return map(uv.x, uv.y); }
  // The Jacobian columns dM/dx and dM/dy at (x, y).
  std::array<Vec2, 2> derivatives(double x, double y) const;

  // Every pre-image of q in the box (default [0,1]^2), ordered by branch. Empty when q is outside the range,
  // q is the fixed point, or no branch lands in the box.
  std::vector<CotsPreimage> inverse(const Vec2& q, const ParameterBox& box = {}) const;
  // The tiles (i, j) of an nu x nv grid that contain q, one per pre-image in [0,1]^2.
  std::vector<std::array<int, 2>> tiles_of(const Vec2& q, int nu, int nv) const;

  // The similarity V^y U^x (so M(x,y) = field(x,y)(a)); U = field(1,0), V = field(0,1).
  Similarity2 field(double x, double y) const;
  Similarity2 u_similarity() const { return field(1.0, 0.0); }
  Similarity2 v_similarity() const { return field(0.0, 1.0); }
  // The similarity taking tile (0,0) of an nu x nv grid onto tile (i,j): field(i/nu, j/nv).
  Similarity2 tile_similarity(int i, int j, int nu, int nv) const;

  // Signed area of the range (negative when the orientation is reversed; overlapping parts count as often as they
  // are covered), in closed form: Im(conj(gu) gv) G(ln|u|) G(ln|v|), G(l) = (e^{2l} - 1)/(2l).
  double area() const;
  // Signed area of tile (i, j) of an nu x nv grid, in closed form.
  double tile_area(int i, int j, int nu, int nv) const;

  Vec2 a() const { return a_; }
  Vec2 b() const { return b_; }
  Vec2 c() const { return c_; }
  Vec2 d() const { return d_; }
  Complex log_u() const { return Lu_; }
  Complex log_v() const { return Lv_; }
  // True on an exact parallelogram: U and V are translations and the map is affine.
  bool is_affine() const { return affine_; }
  // The common fixed point f of U and V; none on a parallelogram.
  std::optional<Vec2> fixed_point() const;
  // The paper's determinant Im(conj(Lu) Lv) (0 on a parallelogram; the inverse divides by it).
  double determinant() const { return Lu_.real() * Lv_.imag() - Lu_.imag() * Lv_.real(); }
  // +1 when the map keeps the orientation of the parameter plane, -1 when it reverses it.
  int orientation() const { return jacobian_factor_ > 0.0 ? 1 : -1; }
  // The angle from the x isocurve to the y isocurve, the same at every point (a tile's angle at its (i,j) corner).
  double tile_angle() const { return std::arg(gv_ / gu_); }

 private:
  friend class BecotsMap;
  struct Unchecked {};
  // Builds without refusing collapsed ranges (a BeCOTS map's shadow on the plane across its axis may be one).
  CotsMap(Unchecked, const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, int branch_u, int branch_v);
  CotsMap() = default;
  void build_from_corners(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, int branch_u, int branch_v);
  void finish(bool check_collapse);
  std::vector<CotsPreimage> affine_inverse(const Vec2& q, const ParameterBox& box) const;
  // The complex logarithm of (q - f)/(a - f), principal, stable near the parallelogram.
  Complex log_ratio(const Vec2& q) const;

  Vec2 a_{0.0}, b_{0.0}, c_{0.0}, d_{0.0};
  Complex Lu_{0.0}, Lv_{0.0};  // log multipliers of U (x) and V (y), with their windings
  Complex gu_{0.0}, gv_{0.0};  // Lu (a - f), Lv (a - f): the map's derivatives at (0,0)
  Complex inv_af_{0.0};        // 1 / (a - f); 0 on a parallelogram
  bool affine_ = false;
  double jacobian_factor_ = 0.0;  // Im(conj(gu) gv): the Jacobian at (0,0)
};

}  // namespace steady
