#include "steady/cots/steady_map2.hpp"

#include <array>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "steady/core/errors.hpp"
#include "steady/core/similarity2d.hpp"
#include "steady/lattice/steady_brick_layout.hpp"

namespace steady {
namespace {

// A planar similarity as the 3D one acting on the plane z = 0, through its generator, so that real powers agree.
Similarity lifted(const Similarity2& s) {
  const Similarity2::Complex L = s.log_multiplier(), w = s.velocity();
  return Similarity::from_generator(L.real(), {0.0, 0.0, L.imag()}, {w.real(), w.imag(), 0.0});
}

void require_finite_point(const Vec2& p, const std::string& name) {
  require_finite(p.x, name);
  require_finite(p.y, name);
}

// Two points a similarity needs apart: closer than 1e-12 of the points' extent they are one point.
void require_apart(const Vec2& p, const Vec2& q, double extent, const std::string& names) {
  if (!(glm::length(p - q) > 1e-12 * extent))
    fail_input(names, "coincide: no similarity maps a point onto two (the map needs them apart)");
}

}  // namespace

SteadyMap2::SteadyMap2(const Similarity& u, const Similarity& v, const Vec3& origin, const Vec3& normal)
    : u_(u), v_(v), origin_(origin), normal_(normal), unit_(glm::length(u.apply_point(origin) - origin)) {}

SteadyMap2 SteadyMap2::from_points(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, const Vec2& e) {
  const char* names[] = {"a", "b", "c", "d", "e"};
  const Vec2 points[] = {a, b, c, d, e};
  double extent = 0.0;
  for (int k = 0; k < 5; ++k) {
    require_finite_point(points[k], names[k]);
    extent = std::max(extent, glm::length(points[k] - a));
  }
  require_apart(a, e, extent, "a, e");
  require_apart(e, b, extent, "e, b");
  require_apart(a, b, extent, "a, b");
  require_apart(c, d, extent, "c, d");
  // U^(1/2) takes a to e and e to b; V takes a to c and b to d.
  const Similarity half = lifted(Similarity2::from_point_pairs(a, e, e, b));
  const Similarity v = lifted(Similarity2::from_point_pairs(a, b, c, d));
  return SteadyMap2(half.power(2.0), v, Vec3(a.x, a.y, 0.0), Vec3(0.0, 0.0, 1.0));
}

SteadyMap2 SteadyMap2::from_frames(const Frame& a, const Frame& b, const Frame& c) {
  validate_frame(a, "a");
  validate_frame(b, "b");
  validate_frame(c, "c");
  const double extent = std::max(glm::length(b.origin - a.origin), glm::length(c.origin - a.origin));
  if (!(glm::length(b.origin - a.origin) > 1e-12 * extent))
    fail_input("b", "its origin coincides with a's: the map would have no extent along u");
  if (!(glm::length(c.origin - a.origin) > 1e-12 * extent))
    fail_input("c", "its origin coincides with a's: the map would have no extent along v");
  return SteadyMap2(Similarity::from_frames(a, b), Similarity::from_frames(a, c), a.origin, glm::normalize(a.z));
}

Similarity SteadyMap2::field(double u, double v) const { return v_.power(v) * u_.power(u); }

Vec3 SteadyMap2::warp(const Vec3& uvw) const {
  return field(uvw.x, uvw.y).apply_point(origin_ + uvw.z * unit_ * normal_);
}

namespace {

// The sphere through four points: its center p0 + x solves 2 (p_i - p0) . x = |p_i - p0|^2 (i = 1..3).
std::optional<Ball> sphere_through(const std::array<Vec3, 4>& p) {
  const Vec3 q1 = p[1] - p[0], q2 = p[2] - p[0], q3 = p[3] - p[0];
  const Mat3 m = glm::transpose(Mat3(q1, q2, q3));  // rows q1, q2, q3
  const double size = std::max({glm::length(q1), glm::length(q2), glm::length(q3)});
  if (!(std::abs(glm::determinant(m)) > 1e-9 * size * size * size)) return std::nullopt;
  const Vec3 x = glm::inverse(m) * Vec3(0.5 * glm::dot(q1, q1), 0.5 * glm::dot(q2, q2), 0.5 * glm::dot(q3, q3));
  return Ball{p[0] + x, glm::length(x)};
}

// The least-squares sphere through points (the algebraic fit |p - m|^2 = 2 c'.(p - m) + k about their mean m,
// linear in c' and k; the radius from k = r^2 - |c'|^2).
std::optional<Ball> sphere_fit(const std::vector<Vec3>& points) {
  Vec3 mean(0.0);
  for (const Vec3& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  glm::dmat4 normal(0.0);
  glm::dvec4 rhs(0.0);
  double size = 0.0;
  for (const Vec3& p : points) {
    const Vec3 q = p - mean;
    const glm::dvec4 row(2.0 * q.x, 2.0 * q.y, 2.0 * q.z, 1.0);
    normal += glm::outerProduct(row, row);
    rhs += glm::dot(q, q) * row;
    size = std::max(size, glm::length(q));
  }
  // Scaled so that the flatness test does not depend on the ball's size.
  const double d = glm::determinant(normal) / (std::pow(size, 6) * std::pow(static_cast<double>(points.size()), 4));
  if (!(std::abs(d) > 1e-12)) return std::nullopt;
  const glm::dvec4 x = glm::inverse(normal) * rhs;
  const Vec3 c(x.x, x.y, x.z);
  const double r2 = x.w + glm::dot(c, c);
  if (!(r2 > 0.0)) return std::nullopt;
  return Ball{mean + c, std::sqrt(r2)};
}

}  // namespace

Ball SteadyMap2::rectify(const Vec3& center, double radius, const std::string& field, Rectification method) const {
  require_finite(center.x, field);
  require_finite(center.y, field);
  require_finite(center.z, field);
  require_positive(radius, field);
  std::optional<Ball> ball;
  if (method == Rectification::FourPoints) {
    const double k = radius / std::sqrt(3.0);
    const std::array<Vec3, 4> corners = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
    std::array<Vec3, 4> p;
    for (int i = 0; i < 4; ++i) p[i] = warp(center + k * corners[i]);
    ball = sphere_through(p);
  } else {
    // 32 directions of a Fibonacci sphere and their opposites.
    constexpr int kHalf = 32;
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    std::vector<Vec3> p;
    for (int i = 0; i < kHalf; ++i) {
      const double z = 1.0 - (i + 0.5) / kHalf, s = std::sqrt(1.0 - z * z), phi = golden * i;
      const Vec3 d(s * std::cos(phi), s * std::sin(phi), z);
      p.push_back(warp(center + radius * d));
      p.push_back(warp(center - radius * d));
    }
    ball = sphere_fit(p);
  }
  if (!ball) fail_input(field, "the map folds the ball flat here (its points map onto one plane)");
  return *ball;
}

Lattice steady_slab_lattice(const SteadyMap2& map, const std::vector<TemplateNode>& nodes,
                            std::vector<BeamPattern> beams, const Counts& counts, double beam_ratio,
                            Rectification method) {
  if (counts.u < 1 || counts.v < 1) fail_input("counts", "each count must be >= 1");
  if (counts.w != 1) fail_input("counts.w", "a steady slab has one layer (got " + std::to_string(counts.w) + ")");
  require_finite(beam_ratio, "beam_ratio");
  if (beam_ratio < 0.0 || beam_ratio > 1.0) fail_input("beam_ratio", "must be 0 (hull beams) or in (0, 1]");
  if (nodes.empty()) fail_input("nodes", "a group needs at least one node");
  const double du = 1.0 / static_cast<double>(counts.u), dv = 1.0 / static_cast<double>(counts.v);
  std::vector<TemplateNode> rectified;
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const Vec3& stw = nodes[n].center;
    const std::string name = "nodes[" + std::to_string(n) + "]";
    require_finite(stw.x, name + ".s");
    require_finite(stw.y, name + ".t");
    const Ball b = map.rectify(Vec3(stw.x * du, stw.y * dv, stw.z), nodes[n].radius, name + ".radius", method);
    rectified.push_back({b.center, b.radius});
  }
  if (beam_ratio > 0.0)
    for (BeamPattern& b : beams) {
      if (b.from < 0 || b.to < 0 || b.from >= static_cast<int>(rectified.size()) ||
          b.to >= static_cast<int>(rectified.size()))
        fail_input("beams", "a beam pattern names a node the group does not have");
      b.from_radius = beam_ratio * rectified[static_cast<std::size_t>(b.from)].radius;
      b.to_radius = beam_ratio * rectified[static_cast<std::size_t>(b.to)].radius;
    }
  const DirectionControl U{map.u().power(du), StepControl::Incremental};
  const DirectionControl V{map.v().power(dv), StepControl::Incremental};
  const DirectionControl W{Similarity::identity(), StepControl::Incremental};
  // Group (i, j) = V^(j dv) o U^(i du) of the template: U applied first (the map's order).
  return Lattice::ordered(std::move(rectified), std::move(beams), counts, U, V, W, Similarity::identity(), {0, 1, 2});
}

}  // namespace steady
