#include "steady/cots/becots_map.hpp"

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
using cots_detail::kTwoPi;

constexpr double kHalfPi = 1.5707963267948966192313216916398;

double max_pairwise_distance(const Vec3 (&p)[4]) {
  double diameter = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) diameter = std::max(diameter, glm::length(p[i] - p[j]));
  return diameter;
}

void require_distinct_adjacent(const Vec3 (&p)[4], double diameter) {
  static const char* const kNames[4] = {"A", "B", "C", "D"};
  if (diameter == 0.0) fail_input("corners A, B, C, D", "all four corners are the same point");
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    if (glm::length(p[j] - p[i]) <= kCotsCoincidenceTolerance * diameter)
      fail_input(std::string("corners ") + kNames[std::min(i, j)] + ", " + kNames[std::max(i, j)],
                 "adjacent corners coincide (the map needs four distinct sides AB, BC, CD, DA)");
  }
}

// The normal of the plane of four coplanar corners: the longest of the cross products of their edge and diagonal
// vectors (any of them may vanish on a self-crossing or degenerate quad, not all unless the corners are collinear).
Vec3 plane_normal(const Vec3 (&p)[4], double diameter) {
  const Vec3 candidates[4] = {glm::cross(p[3] - p[0], p[1] - p[0]), glm::cross(p[1] - p[2], p[3] - p[2]),
                              glm::cross(p[2] - p[0], p[3] - p[1]), glm::cross(p[2] - p[0], p[1] - p[0])};
  Vec3 best = candidates[0];
  for (const Vec3& n : candidates)
    if (glm::length(n) > glm::length(best)) best = n;
  if (!(glm::length(best) > kCotsCollapseTolerance * diameter * diameter))
    fail_input("corners A, B, C, D", "the corners lie on one line: their range is a curve, not a surface");
  return best / glm::length(best);
}

// The axis of the commuting rotations: it must be orthogonal to unit(DC) - unit(AB) (the rotation turns AB's
// direction into DC's) and to unit(BC) - unit(AD).
Vec3 cone_axis(const Vec3 (&p)[4]) {
  const Vec3 turn_u = glm::normalize(p[2] - p[3]) - glm::normalize(p[1] - p[0]);
  const Vec3 turn_v = glm::normalize(p[2] - p[1]) - glm::normalize(p[3] - p[0]);
  const Vec3 n = glm::cross(turn_u, turn_v);
  if (!(glm::length(n) > kBecotsAxisTolerance)) {
    std::ostringstream os;
    os << "the axis of the cone is undetermined (|(unit(DC) - unit(AB)) x (unit(BC) - unit(AD))| = " << glm::length(n)
       << " <= " << kBecotsAxisTolerance
       << "): a family of fields passes through these corners, as when AB is nearly parallel to DC, or when "
          "|AB| = |CD| and |AD| = |BC| (coaxial screws on cylinders of many axes)";
    fail_input("corners A, B, C, D", os.str());
  }
  return n / glm::length(n);
}

bool clamp_into(double* value, double lo, double hi) {
  if (!(*value >= lo - kCotsParameterTolerance && *value <= hi + kCotsParameterTolerance)) return false;
  *value = std::clamp(*value, lo, hi);
  return true;
}

}  // namespace

void BecotsMap::set_axis(const Vec3& axis) {
  axis_ = axis;
  // plane_x across the axis, from the coordinate axis least aligned with it; plane_x x plane_y = axis.
  const Vec3 e = std::abs(axis.x) <= std::abs(axis.y) && std::abs(axis.x) <= std::abs(axis.z) ? Vec3(1, 0, 0)
                 : std::abs(axis.y) <= std::abs(axis.z)                                    ? Vec3(0, 1, 0)
                                                                                           : Vec3(0, 0, 1);
  plane_x_ = glm::normalize(glm::cross(e, axis));
  plane_y_ = glm::cross(axis, plane_x_);
}

Vec2 BecotsMap::shadow_of(const Vec3& q) const {
  const Vec3 e = q - a_;
  return {glm::dot(e, plane_x_), glm::dot(e, plane_y_)};
}

BecotsMap::Complex BecotsMap::shadow_ratio(const Vec3& q) const {
  const Vec2 s = shadow_of(q);
  return 1.0 + Complex(s.x, s.y) * shadow_.inv_af_;
}

BecotsMap::BecotsMap(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int branch_u, int branch_v) {
  require_within(a, kMaxCoordinate, "corner A");
  require_within(b, kMaxCoordinate, "corner B");
  require_within(c, kMaxCoordinate, "corner C");
  require_within(d, kMaxCoordinate, "corner D");
  const Vec3 p[4] = {a, b, c, d};
  const double diameter = max_pairwise_distance(p);
  require_distinct_adjacent(p, diameter);
  a_ = a, b_ = b, c_ = c, d_ = d;
  const double volume = std::abs(glm::dot(b - a, glm::cross(c - a, d - a)));
  flat_ = volume <= kBecotsCoplanarTolerance * diameter * diameter * diameter;
  Vec3 axis = flat_ ? plane_normal(p, diameter) : cone_axis(p);
  try {
    // The axis' sense: the one about which the principal shadow turns counterclockwise.
    set_axis(axis);
    const CotsMap principal(CotsMap::Unchecked{}, {0.0, 0.0}, shadow_of(b), shadow_of(c), shadow_of(d), 0, 0);
    if (principal.orientation() < 0) set_axis(-axis);
    shadow_ = CotsMap(CotsMap::Unchecked{}, {0.0, 0.0}, shadow_of(b), shadow_of(c), shadow_of(d), branch_u, branch_v);
    if (flat_) shadow_.finish(true);
  } catch (const InvalidInput& e) {
    fail_input("corners A, B, C, D", std::string("their shadows on the plane across the axis fail: ") + e.what());
  }
  if (!flat_) {
    hu_ = glm::dot(d - a, axis_) / cots_detail::phi(shadow_.log_u().real());
    hv_ = glm::dot(b - a, axis_) / cots_detail::phi(shadow_.log_v().real());
  }
  finish();
  const double miss = std::max({glm::length(map(0.0, 1.0) - b), glm::length(map(1.0, 1.0) - c),
                                glm::length(map(1.0, 0.0) - d)});
  if (!(miss <= kBecotsSurfaceTolerance * diameter)) {
    std::ostringstream os;
    os << "no BeCOTS field passes through these corners (the best field misses them by " << miss << ")";
    fail_input("corners A, B, C, D", os.str());
  }
}

BecotsMap BecotsMap::from_field(const Vec3& apex, const Vec3& axis, const Vec3& a, Complex log_u, Complex log_v) {
  require_within(apex, kMaxCoordinate, "apex");
  require_within(axis, kMaxCoordinate, "axis");
  require_within(a, kMaxCoordinate, "a");
  if (!(glm::length(axis) > 0.0)) fail_input("axis", "must be a non-zero vector");
  BecotsMap m;
  m.a_ = a;
  m.set_axis(glm::normalize(axis));
  const Vec3 fa = a - apex;
  const Vec2 radial{glm::dot(fa, m.plane_x_), glm::dot(fa, m.plane_y_)};
  if (!(glm::length(radial) > kCotsCoincidenceTolerance * glm::length(fa)))
    fail_input("a", "lies on the axis through the apex: its range would be a segment of the axis");
  m.shadow_ = CotsMap::from_spiral({0.0, 0.0}, -radial, log_u, log_v);
  double height = glm::dot(fa, m.axis_);
  m.flat_ = std::abs(height) <= kBecotsCoplanarTolerance * glm::length(fa);
  if (m.flat_) height = 0.0;
  m.hu_ = height * log_u.real();
  m.hv_ = height * log_v.real();
  m.finish();
  m.b_ = m.map(0.0, 1.0);
  m.c_ = m.map(1.0, 1.0);
  m.d_ = m.map(1.0, 0.0);
  const Vec3 p[4] = {m.a_, m.b_, m.c_, m.d_};
  m.diameter_ = max_pairwise_distance(p);
  return m;
}

void BecotsMap::finish() {
  const Vec3 p[4] = {a_, b_, c_, d_};
  diameter_ = max_pairwise_distance(p);
  const double lu = shadow_.log_u().real(), lv = shadow_.log_v().real();
  radial_ = shadow_.inv_af_ == 0.0 ? Complex(INFINITY, 0.0) : 1.0 / shadow_.inv_af_;
  height_ = 0.0;
  if (flat_ && !std::isfinite(std::abs(radial_))) return;  // a parallelogram: the shadow (affine) does everything
  // Off the plane, neither can happen to a field through four corners (their axis would be undetermined), but a
  // shadow that is a parallelogram, or no dilation at all, would leave the field without an apex.
  if (!std::isfinite(std::abs(radial_)) || (!flat_ && lu == 0.0 && lv == 0.0))
    fail_input("corners A, B, C, D", "the field has no apex: its range is not on a cone");
  const double r = std::abs(radial_);
  const Vec3 radial3 = embed({radial_.real(), radial_.imag()});
  if (!flat_) height_ = std::abs(lu) >= std::abs(lv) ? hu_ / lu : hv_ / lv;
  const double length = std::hypot(r, height_);
  inv_length_ = 1.0 / length;
  radial_dir_ = (radial3 + height_ * axis_) * inv_length_;
  pu_ = lu * length, pv_ = lv * length;
  qu_ = shadow_.log_u().imag() * r, qv_ = shadow_.log_v().imag() * r;
  if (flat_) return;  // the shadow checked its own collapse; its inverse and area are used
  const double det = pu_ * qv_ - pv_ * qu_;
  const double sine = std::abs(det) / (std::hypot(pu_, qu_) * std::hypot(pv_, qv_));
  if (!(sine > kCotsCollapseTolerance)) {
    std::ostringstream os;
    os << "the range collapses to a curve on its cone (|sin| of the isocurves' angle = " << sine << " <= "
       << kCotsCollapseTolerance << ")";
    fail_input("corners A, B, C, D", os.str());
  }
}

Vec3 BecotsMap::map(double x, double y) const {
  const Vec2 s = shadow_.map(x, y);
  Vec3 m = a_ + embed(s);
  if (!flat_) {
    const double sigma = x * shadow_.log_u().real() + y * shadow_.log_v().real();
    m += (cots_detail::phi(sigma) * (x * hu_ + y * hv_)) * axis_;
  }
  return m;
}

std::vector<CotsPreimage> BecotsMap::solve_cone(const Vec3& q, const ParameterBox& box) const {
  // Two real equations, each scaled to a length so that the system stays well conditioned from flat cones to
  // cylinders: x pu + y pv = |A - F| ln(|Q - F| / |A - F|) (along the generator) and x qu + y qv = |a' - f'| angle
  // (the arc about the axis, from the shadows).
  const Complex z = shadow_ratio(q);
  if (z == 0.0) return {};  // q on the axis: no angle
  const double angle0 = std::arg(z);
  const Vec3 e = q - a_;
  // |Q - F|^2 / |A - F|^2 = 1 + t / |A - F| with t = 2 e.n + |e|^2 / |A - F|; the log is taken without forming F.
  const double t = 2.0 * glm::dot(e, radial_dir_) + inv_length_ * glm::dot(e, e);
  if (!(1.0 + inv_length_ * t > 0.0)) return {};  // q is the apex
  const double along = 0.5 * t * cots_detail::log1p_ratio(inv_length_ * t);
  const double r = std::abs(radial_);
  const double wu = shadow_.log_u().imag(), wv = shadow_.log_v().imag();
  const double corner_angles[4] = {box.x0 * wu + box.y0 * wv, box.x1 * wu + box.y0 * wv, box.x0 * wu + box.y1 * wv,
                                   box.x1 * wu + box.y1 * wv};
  long first = 0, last = 0;
  cots_detail::branch_range(angle0, *std::min_element(corner_angles, corner_angles + 4),
                            *std::max_element(corner_angles, corner_angles + 4), &first, &last);
  const double det = pu_ * qv_ - pv_ * qu_;
  std::vector<CotsPreimage> found;
  for (long k = first; k <= last; ++k) {
    const double arc = (angle0 + kTwoPi * static_cast<double>(k)) * r;
    double x = (along * qv_ - pv_ * arc) / det, y = (pu_ * arc - qu_ * along) / det;
    if (clamp_into(&x, box.x0, box.x1) && clamp_into(&y, box.y0, box.y1))
      found.push_back({{x, y}, static_cast<int>(k)});
  }
  return found;
}

std::vector<CotsPreimage> BecotsMap::inverse(const Vec3& q, const ParameterBox& box, double tolerance) const {
  require_within(q, kMaxCoordinate, "q");
  require_positive(tolerance, "tolerance");
  if (!(box.x0 <= box.x1) || !(box.y0 <= box.y1)) fail_input("box", "expected x0 <= x1 and y0 <= y1");
  std::vector<CotsPreimage> found = flat_ ? shadow_.inverse(shadow_of(q), box) : solve_cone(q, box);
  const double reach = tolerance * (diameter_ + glm::length(q - a_));
  found.erase(std::remove_if(found.begin(), found.end(),
                             [&](const CotsPreimage& p) { return !(glm::length(map(p.uv) - q) <= reach); }),
              found.end());
  return found;
}

std::vector<std::array<int, 2>> BecotsMap::tiles_of(const Vec3& q, int nu, int nv) const {
  require_grid(nu, nv);
  return tiles_of_preimages(inverse(q), nu, nv);
}

Similarity BecotsMap::field(double x, double y) const {
  require_finite(x, "x");
  require_finite(y, "y");
  // The generator p -> sigma p + omega x p + v vanishes at the apex F: v = sigma (A - F) + omega x (A - F) - sigma A
  // - omega x A, where sigma (A - F) + omega x (A - F) = embed(x gu + y gv) + (x hu + y hv) T needs no F.
  const Complex L = x * shadow_.log_u() + y * shadow_.log_v();
  const Complex g = x * shadow_.gu_ + y * shadow_.gv_;
  const Vec3 omega = L.imag() * axis_;
  const Vec3 v = embed({g.real(), g.imag()}) + (x * hu_ + y * hv_) * axis_ - L.real() * a_ - glm::cross(omega, a_);
  return Similarity::from_generator(L.real(), omega, v);
}

Similarity BecotsMap::tile_similarity(int i, int j, int nu, int nv) const {
  require_grid(nu, nv);
  return field(static_cast<double>(i) / nu, static_cast<double>(j) / nv);
}

double BecotsMap::area() const {
  if (flat_) return std::abs(shadow_.area());
  // |dM/dx x dM/dy| = e^{2 sigma} |pu qv - pv qu|: the factor |A - F| |a' - f'| |Im(conj(Lu) Lv)| in stable form.
  return std::abs(pu_ * qv_ - pv_ * qu_) * cots_detail::exp2_integral(shadow_.log_u().real(), 1.0) *
         cots_detail::exp2_integral(shadow_.log_v().real(), 1.0);
}

double BecotsMap::tile_area(int i, int j, int nu, int nv) const {
  require_grid(nu, nv);
  if (flat_) return std::abs(shadow_.tile_area(i, j, nu, nv));
  const double lu = shadow_.log_u().real(), lv = shadow_.log_v().real();
  return std::abs(pu_ * qv_ - pv_ * qu_) * std::exp(2.0 * (lu * i / nu + lv * j / nv)) *
         cots_detail::exp2_integral(lu, 1.0 / nu) * cots_detail::exp2_integral(lv, 1.0 / nv);
}

std::optional<Vec3> BecotsMap::apex() const {
  if (!std::isfinite(std::abs(radial_))) return std::nullopt;
  return a_ - embed({radial_.real(), radial_.imag()}) - height_ * axis_;
}

double BecotsMap::height() const { return height_; }

Vec3 BecotsMap::normal() const {
  // The derivatives at (0, 0) without the apex: dM/dx = embed(Lu (a - f)) + hu T, likewise for y (see field()).
  const Vec3 du = embed({shadow_.gu_.real(), shadow_.gu_.imag()}) + hu_ * axis_;
  const Vec3 dv = embed({shadow_.gv_.real(), shadow_.gv_.imag()}) + hv_ * axis_;
  return glm::normalize(glm::cross(du, dv));
}

BecotsMap BecotsMap::raised(double z) const {
  require_within(z, kMaxCoordinate, "z");
  BecotsMap m = *this;
  const double lu = shadow_.log_u().real(), lv = shadow_.log_v().real();
  m.a_ = a_ + z * axis_;
  m.hu_ = hu_ + z * lu;
  m.hv_ = hv_ + z * lv;
  // Raising moves every point by z m_u^x m_v^y along the axis: without dilation that is a translation.
  m.flat_ = flat_ && lu == 0.0 && lv == 0.0;
  m.b_ = m.map(0.0, 1.0);
  m.c_ = m.map(1.0, 1.0);
  m.d_ = m.map(1.0, 0.0);
  m.finish();
  return m;
}

BecotsMap BecotsMap::projected() const {
  if (flat_) return *this;
  BecotsMap m = raised(-height_);
  m.flat_ = true;
  m.hu_ = m.hv_ = 0.0;
  m.finish();
  return m;
}

double BecotsMap::bend_angle() const {
  if (flat_) return kHalfPi;
  const Vec3 fa = embed({radial_.real(), radial_.imag()}) + height_ * axis_;
  return std::atan2(glm::length(glm::cross(fa, axis_)), glm::dot(fa, axis_));
}

BecotsMap BecotsMap::unbent() const {
  if (flat_) return *this;
  const std::optional<Vec3> f = apex();
  if (!f) fail_input("unbent", "the field has no apex to unroll the sheet about");
  const double beta = bend_angle();
  const Vec3 unit_fa = glm::normalize(a_ - *f);
  // The axis tilted within the plane of T and FA until it is orthogonal to FA; angles about it grow by sin(beta).
  const Vec3 flat_axis = glm::normalize(axis_ - unit_fa * glm::dot(unit_fa, axis_));
  const double s = std::sin(beta);
  const Complex lu = shadow_.log_u(), lv = shadow_.log_v();
  return from_field(*f, flat_axis, a_, {lu.real(), lu.imag() * s}, {lv.real(), lv.imag() * s});
}

BecotsMap BecotsMap::bent(double beta) const {
  require_finite(beta, "beta");
  if (!(beta > 0.0 && beta < 2.0 * kHalfPi)) fail_input("beta", "must be in (0, pi) (got " + std::to_string(beta) + ")");
  const BecotsMap sheet = unbent();
  const std::optional<Vec3> f = sheet.apex();
  if (!f) fail_input("bent", "a parallelogram's field has no apex to roll the sheet about");
  const Vec3 unit_fa = glm::normalize(a_ - *f);
  const double tilt = kHalfPi - beta;  // the axis turns toward FA by pi/2 - beta
  const Vec3 axis = sheet.axis_ * std::cos(tilt) + unit_fa * std::sin(tilt);
  const double s = std::sin(beta);
  const Complex lu = sheet.log_u(), lv = sheet.log_v();
  return from_field(*f, axis, a_, {lu.real(), lu.imag() / s}, {lv.real(), lv.imag() / s});
}

}  // namespace steady
