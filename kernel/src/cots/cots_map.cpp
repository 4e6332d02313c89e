#include "steady/cots/cots_map.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "cots/cots_math.hpp"
#include "steady/core/errors.hpp"
#include "cots/cots_grid.hpp"
#include "steady/core/numeric_range.hpp"

namespace steady {
namespace {
using cots_detail::Complex;
using cots_detail::cross;
using cots_detail::kTwoPi;

Complex to_complex(const Vec2& p) { return {p.x, p.y}; }
Vec2 to_vec(Complex z) { return {z.real(), z.imag()}; }

void require_point(const Vec2& p, const std::string& name) {
  require_within(p.x, kMaxCoordinate, name + ".x");
  require_within(p.y, kMaxCoordinate, name + ".y");
}

void require_branch(int k, const char* name) {
  if (k < -kCotsMaxBranch || k > kCotsMaxBranch)
    fail_input(name, "must be within +-" + std::to_string(kCotsMaxBranch) + " turns (got " + std::to_string(k) + ")");
}


// Refuses corners where two adjacent ones coincide (the multipliers |cd|/|ab|, |bc|/|ad| would be 0 or infinite).
void require_distinct_adjacent(const Complex (&p)[4]) {
  static const char* const kNames[4] = {"a", "b", "c", "d"};
  double diameter = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) diameter = std::max(diameter, std::abs(p[i] - p[j]));
  if (diameter == 0.0) fail_input("corners a, b, c, d", "all four corners are the same point");
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    if (std::abs(p[j] - p[i]) <= kCotsCoincidenceTolerance * diameter)
      fail_input(std::string("corners ") + kNames[std::min(i, j)] + ", " + kNames[std::max(i, j)],
                 "adjacent corners coincide (the map needs four distinct sides ab, bc, cd, da)");
  }
}

// Clamps a value that lies within the tolerance of [lo, hi] onto it; false when it lies further out.
bool clamp_into(double* value, double lo, double hi) {
  if (!(*value >= lo - kCotsParameterTolerance && *value <= hi + kCotsParameterTolerance)) return false;
  *value = std::clamp(*value, lo, hi);
  return true;
}
}  // namespace

CotsMap::CotsMap(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, int branch_u, int branch_v) {
  build_from_corners(a, b, c, d, branch_u, branch_v);
  finish(true);
}

CotsMap::CotsMap(Unchecked, const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, int branch_u, int branch_v) {
  build_from_corners(a, b, c, d, branch_u, branch_v);
  finish(false);
}

void CotsMap::build_from_corners(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, int branch_u,
                                 int branch_v) {
  require_point(a, "corner a");
  require_point(b, "corner b");
  require_point(c, "corner c");
  require_point(d, "corner d");
  require_branch(branch_u, "branch_u");
  require_branch(branch_v, "branch_v");
  const Complex p[4] = {to_complex(a), to_complex(b), to_complex(c), to_complex(d)};
  require_distinct_adjacent(p);
  a_ = a, b_ = b, c_ = c, d_ = d;
  const Complex A = p[0], B = p[1], C = p[2], D = p[3];
  // u - 1 = (a - b + c - d)/(b - a) and v - 1 = (a - b + c - d)/(d - a), formed directly so that their logarithms
  // keep full relative accuracy near the parallelogram (where u, v -> 1).
  const Complex den = A - B + C - D;
  if (den == 0.0 && (branch_u != 0 || branch_v != 0))
    fail_input("branch_u, branch_v", "corners a, b, c, d form a parallelogram: U and V are translations, which "
                                     "have no windings (use branches 0, 0)");
  affine_ = den == 0.0;
  Lu_ = cots_detail::log1p(den / (B - A)) + Complex(0.0, kTwoPi * branch_u);
  Lv_ = cots_detail::log1p(den / (D - A)) + Complex(0.0, kTwoPi * branch_v);
  // gu = Lu (a - f) = (d - a) Lu / (u - 1), finite at the parallelogram (then d - a).
  gu_ = (D - A) / cots_detail::phi(Lu_);
  gv_ = (B - A) / cots_detail::phi(Lv_);
  inv_af_ = den / ((D - A) * (B - A));  // 1/(a - f), with a - f = (d - a)(b - a)/(a - b + c - d)
}

CotsMap CotsMap::from_spiral(const Vec2& a, const Vec2& center, Complex log_u, Complex log_v) {
  require_point(a, "a");
  require_point(center, "center");
  require_within(log_u.real(), kMaxLogScale, "log_u.real");
  require_within(log_u.imag(), kMaxAngle, "log_u.imag");
  require_within(log_v.real(), kMaxLogScale, "log_v.real");
  require_within(log_v.imag(), kMaxAngle, "log_v.imag");
  const Complex r = to_complex(a) - to_complex(center);
  if (r == 0.0) fail_input("a, center", "the corner a must differ from the fixed point");
  const Complex F = to_complex(center);
  CotsMap m;
  m.a_ = a;
  m.b_ = to_vec(F + std::exp(log_v) * r);
  m.c_ = to_vec(F + std::exp(log_u + log_v) * r);
  m.d_ = to_vec(F + std::exp(log_u) * r);
  const Complex p[4] = {to_complex(m.a_), to_complex(m.b_), to_complex(m.c_), to_complex(m.d_)};
  require_distinct_adjacent(p);
  m.Lu_ = log_u;
  m.Lv_ = log_v;
  m.gu_ = log_u * r;
  m.gv_ = log_v * r;
  m.inv_af_ = 1.0 / r;
  m.affine_ = false;
  m.finish(true);
  return m;
}

void CotsMap::finish(bool check_collapse) {
  jacobian_factor_ = cross(gu_, gv_);
  if (!check_collapse) return;
  const double sine = std::abs(jacobian_factor_) / (std::abs(gu_) * std::abs(gv_));
  if (!(sine > kCotsCollapseTolerance)) {
    std::ostringstream os;
    os << "the range collapses to a curve: the x and y isocurves cross at " << std::arg(gv_ / gu_)
       << " rad (|sin| = " << sine << " <= " << kCotsCollapseTolerance << "), "
       << (affine_ ? "the parallelogram is flat (its corners are collinear)"
                   : "log_u and log_v are real multiples of each other");
    fail_input("corners a, b, c, d", os.str());
  }
}

Vec2 CotsMap::map(double x, double y) const {
  const Complex Z = x * Lu_ + y * Lv_;
  return to_vec(to_complex(a_) + cots_detail::phi(Z) * (x * gu_ + y * gv_));
}

std::array<Vec2, 2> CotsMap::derivatives(double x, double y) const {
  const Complex e = std::exp(x * Lu_ + y * Lv_);
  return {to_vec(e * gu_), to_vec(e * gv_)};
}

std::optional<Vec2> CotsMap::fixed_point() const {
  if (inv_af_ == 0.0) return std::nullopt;
  return to_vec(to_complex(a_) - 1.0 / inv_af_);
}

CotsMap::Complex CotsMap::log_ratio(const Vec2& q) const {
  // (q - f)/(a - f) = 1 + (q - a)/(a - f)
  return cots_detail::log1p((to_complex(q) - to_complex(a_)) * inv_af_);
}

std::vector<CotsPreimage> CotsMap::affine_inverse(const Vec2& q, const ParameterBox& box) const {
  const Complex e = to_complex(q) - to_complex(a_);
  const double det = cross(gu_, gv_);  // gu = d - a, gv = b - a here
  double x = cross(e, gv_) / det, y = cross(gu_, e) / det;
  if (!clamp_into(&x, box.x0, box.x1) || !clamp_into(&y, box.y0, box.y1)) return {};
  return {CotsPreimage{{x, y}, 0}};
}

std::vector<CotsPreimage> CotsMap::inverse(const Vec2& q, const ParameterBox& box) const {
  require_point(q, "q");
  if (!(box.x0 <= box.x1) || !(box.y0 <= box.y1)) fail_input("box", "expected x0 <= x1 and y0 <= y1");
  if (affine_) return affine_inverse(q, box);
  // q = f + exp(x Lu + y Lv)(a - f)  <=>  x Lu + y Lv = Log((q - f)/(a - f)) + 2 pi i k, a real 2 x 2 system per k.
  const Complex z1 = (to_complex(q) - to_complex(a_)) * inv_af_;
  if (z1 == -1.0) return {};  // q is the fixed point, which the map never reaches
  const Complex w0 = cots_detail::log1p(z1);
  const double corner_angles[4] = {box.x0 * Lu_.imag() + box.y0 * Lv_.imag(), box.x1 * Lu_.imag() + box.y0 * Lv_.imag(),
                                   box.x0 * Lu_.imag() + box.y1 * Lv_.imag(), box.x1 * Lu_.imag() + box.y1 * Lv_.imag()};
  const double alpha_min = *std::min_element(corner_angles, corner_angles + 4);
  const double alpha_max = *std::max_element(corner_angles, corner_angles + 4);
  long first = 0, last = 0;
  cots_detail::branch_range(w0.imag(), alpha_min, alpha_max, &first, &last);
  const double det = determinant();
  std::vector<CotsPreimage> found;
  for (long k = first; k <= last; ++k) {
    const Complex w = w0 + Complex(0.0, kTwoPi * static_cast<double>(k));
    double x = -cross(Lv_, w) / det, y = cross(Lu_, w) / det;  // Cramer's rule
    if (clamp_into(&x, box.x0, box.x1) && clamp_into(&y, box.y0, box.y1))
      found.push_back({{x, y}, static_cast<int>(k)});
  }
  return found;
}

void require_grid(int nu, int nv) {
  if (nu < 1) fail_input("nu", "must be >= 1 (got " + std::to_string(nu) + ")");
  if (nv < 1) fail_input("nv", "must be >= 1 (got " + std::to_string(nv) + ")");
}

std::vector<std::array<int, 2>> tiles_of_preimages(const std::vector<CotsPreimage>& preimages, int nu, int nv) {
  std::vector<std::array<int, 2>> tiles;
  for (const CotsPreimage& p : preimages) {
    const int i = std::min(static_cast<int>(std::floor(p.uv.x * nu)), nu - 1);
    const int j = std::min(static_cast<int>(std::floor(p.uv.y * nv)), nv - 1);
    tiles.push_back({i, j});
  }
  return tiles;
}

std::vector<std::array<int, 2>> CotsMap::tiles_of(const Vec2& q, int nu, int nv) const {
  require_grid(nu, nv);
  return tiles_of_preimages(inverse(q), nu, nv);
}

Similarity2 CotsMap::field(double x, double y) const {
  require_finite(x, "x");
  require_finite(y, "y");
  // The generator z -> L z + w vanishes at f: w = -L f = L (a - f) - L a = x gu + y gv - L a (finite without f).
  const Complex L = x * Lu_ + y * Lv_;
  return Similarity2::from_generator(L, x * gu_ + y * gv_ - L * to_complex(a_));
}

Similarity2 CotsMap::tile_similarity(int i, int j, int nu, int nv) const {
  require_grid(nu, nv);
  return field(static_cast<double>(i) / nu, static_cast<double>(j) / nv);
}

double CotsMap::area() const {
  // The Jacobian is Im(conj(gu) gv) e^{2 (x ln|u| + y ln|v|)}; integrate over [0,1]^2.
  return jacobian_factor_ * cots_detail::exp2_integral(Lu_.real(), 1.0) *
         cots_detail::exp2_integral(Lv_.real(), 1.0);
}

double CotsMap::tile_area(int i, int j, int nu, int nv) const {
  require_grid(nu, nv);
  const double lu = Lu_.real(), lv = Lv_.real();
  return jacobian_factor_ * std::exp(2.0 * (lu * i / nu + lv * j / nv)) *
         cots_detail::exp2_integral(lu, 1.0 / nu) * cots_detail::exp2_integral(lv, 1.0 / nv);
}

}  // namespace steady
