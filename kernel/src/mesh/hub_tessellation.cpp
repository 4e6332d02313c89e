#include "mesh/hub_tessellation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "core/cell_grid.hpp"
#include "lattice/circle_frames.hpp"
#include "mesh/sphere_hull.hpp"
#include "steady/core/errors.hpp"

namespace steady {

namespace {

[[noreturn]] void internal_error(const std::string& what) { throw std::runtime_error("mesh: " + what); }

// Sphere points are spread so that the Delaunay triangles' circumradius a (chord error a^2 / 2 on the unit sphere)
// stays within the tolerance; the Fibonacci spiral's triangles are near-equilateral, and 0.8 covers the rest.
double point_spacing(double tolerance) { return std::min(0.5, 0.8 * std::sqrt(6.0 * tolerance)); }

// Points spread evenly over the unit sphere (Fibonacci spiral) at the given spacing (area sqrt(3)/2 s^2 each).
int sphere_points_at(double spacing) {
  return std::max(12, static_cast<int>(std::ceil(8.0 * M_PI / (std::sqrt(3.0) * spacing * spacing))));
}

std::vector<Vec3> sphere_points(double spacing) {
  const int n = sphere_points_at(spacing);
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  std::vector<Vec3> points(n);
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt((1.0 - z) * (1.0 + z));
    points[i] = Vec3(r * std::cos(i * golden_angle), r * std::sin(i * golden_angle), z);
  }
  return points;
}

// The n vertices of the circle of radius `radius` around unit `direction` at axial `position`, counterclockwise
// about the direction, starting `phase` steps past the direction's reference perpendicular (circle_frames.hpp).
std::vector<Vec3> circle_points(const Vec3& direction, double position, double radius, int n, double phase = 0.0) {
  const Vec3 e1 = any_perpendicular(direction), e2 = glm::cross(direction, e1);
  std::vector<Vec3> points(n);
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * (i + phase) / n;
    points[i] = position * direction + radius * (std::cos(t) * e1 + std::sin(t) * e2);
  }
  return points;
}

// Drops the faces of a sphere triangulation with all three corners on one ring (the ring's cap: every other point
// lies outside it), checking that each ring of n points lost exactly the n - 2 triangles of its polygon.
std::vector<Triangle> without_ring_caps(const std::vector<Triangle>& triangles, const std::vector<int>& ring_of,
                                        const std::vector<std::vector<std::uint32_t>>& rings) {
  std::vector<Triangle> kept;
  std::vector<std::size_t> dropped(rings.size(), 0);
  for (const Triangle& t : triangles) {
    const int k = ring_of[t[0]];
    if (k >= 0 && ring_of[t[1]] == k && ring_of[t[2]] == k) {
      ++dropped[k];
      continue;
    }
    kept.push_back(t);
  }
  for (std::size_t k = 0; k < rings.size(); ++k)
    if (dropped[k] + 2 != rings[k].size())
      internal_error("the sphere of a hub does not hold circle " + std::to_string(k) + " as a face");
  return kept;
}

// The boundary of a crowded hub up to its collars, seen from the ball's center: along each direction w outside the
// collars' cones, the piece (sphere or stump) that reaches farthest, and how far.
struct RadialHub {
  RadialHub(const std::vector<CoreStump>& stumps, const std::vector<double>& collars) : stumps(stumps) {
    for (std::size_t k = 0; k < stumps.size(); ++k) reaches.emplace_back(stumps[k], collars[k]);
  }
  const std::vector<CoreStump>& stumps;
  std::vector<StumpReach> reaches;

  static constexpr int kSphere = -1;
  double reach(int piece, const Vec3& w) const { return piece == kSphere ? 1.0 : reaches[piece](w); }
  int piece(const Vec3& w) const {
    return farthest(w, reaches.size(), [](std::size_t i) { return static_cast<int>(i); });
  }
  // The piece reaching farthest along w among the sphere and the stumps stump(0) .. stump(n - 1).
  template <class Stump>
  int farthest(const Vec3& w, std::size_t n, const Stump& stump) const {
    int best = kSphere;
    double far = 1.0;
    for (std::size_t i = 0; i < n; ++i) {
      const int k = stump(i);
      const double r = reaches[k].beyond_ball(w);
      if (r > far) far = r, best = k;
    }
    return best;
  }
  // piece(w) for w on the arc between unit a and b: only the stumps that can reach beyond the ball somewhere on
  // it are asked (along the arc the cos to an axis moves by at most the chord |b - a|), so the answer is
  // piece's, bit for bit, for a few dot products.
  struct ArcPieces {
    ArcPieces(const RadialHub& hub, const Vec3& a, const Vec3& b) : hub(hub) {
      const double reach = glm::length(b - a) + 1e-12;
      for (std::size_t k = 0; k < hub.reaches.size(); ++k) {
        const StumpReach& s = hub.reaches[k];
        if (std::max(glm::dot(s.axis(), a), glm::dot(s.axis(), b)) + reach >= s.exit_k())
          near.push_back(static_cast<int>(k));
      }
    }
    int operator()(const Vec3& w) const {
      return hub.farthest(w, near.size(), [this](std::size_t i) { return near[i]; });
    }
    const RadialHub& hub;
    std::vector<int> near;
  };
  double radius(const Vec3& w) const { return reach(piece(w), w); }
  // How far point p lies outside the hub (the ball and the stumps' cones): > 0 only outside every piece, where
  // it is the exact distance to the nearest one; <= 0 inside some piece. A chord across a concave crease (a cone
  // meeting the sphere, or two cones) lies outside, and the distance of the triangle's plane to the surface point
  // along the chord's direction misses it when the triangle stands steep: 142 edge midpoints of the main job's
  // crowded hubs lay up to 1.2 times the tolerance outside.
  double outside(const Vec3& p) const {
    double d = glm::length(p) - 1.0;
    for (std::size_t k = 0; k < stumps.size(); ++k) {
      const CoreStump& s = stumps[k];
      const Vec3& axis = reaches[k].axis();
      const double x = glm::dot(p, axis);
      // Below the plane where the cone touches its end ball the ball covers; beyond the collar the beam goes on (the
      // strips continue the cone), so the cone counts there too.
      if (x < s.end_radius * s.sin_phi) continue;
      d = std::min(d, reaches[k].cos_phi() * (glm::length(p - x * axis) - s.radius_at(x)));  // to the cone's generator
    }
    return d;
  }
};

// The point where the pieces change along the arc from a (on piece `at_a`) to b: bisection to rounding.
Vec3 crease_on_arc(const RadialHub& hub, const Vec3& a, const Vec3& b, int at_a) {
  const RadialHub::ArcPieces piece(hub, a, b);
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (piece(glm::normalize((1.0 - mid) * a + mid * b)) == at_a ? lo : hi) = mid;
  }
  return glm::normalize((1.0 - hi) * a + hi * b);
}

// Where three pieces meet near w: Gauss-Newton on (reach_a - reach_b, reach_b - reach_c) over the tangent plane,
// with difference quotients; w itself when it does not converge within `step`.
Vec3 triple_point(const RadialHub& hub, const Vec3& w, const std::array<int, 3>& p, double step) {
  const Vec3 u = any_perpendicular(w), v = glm::cross(w, u);
  auto residual = [&](double x, double y) {
    const Vec3 q = glm::normalize(w + x * u + y * v);
    return glm::dvec2(hub.reach(p[0], q) - hub.reach(p[1], q), hub.reach(p[1], q) - hub.reach(p[2], q));
  };
  double x = 0.0, y = 0.0;
  constexpr double h = 1e-7;
  for (int it = 0; it < 20; ++it) {
    const glm::dvec2 r = residual(x, y);
    if (glm::length(r) < 1e-14) break;
    const glm::dvec2 dx = (residual(x + h, y) - r) / h, dy = (residual(x, y + h) - r) / h;
    const double det = dx.x * dy.y - dx.y * dy.x;
    if (!(std::abs(det) > 1e-300)) return w;
    x -= (r.x * dy.y - r.y * dy.x) / det;
    y -= (dx.x * r.y - dx.y * r.x) / det;
    if (std::hypot(x, y) > step) return w;
  }
  return glm::normalize(w + x * u + y * v);
}

// Points within `radius` of each other, found through a grid of that cell size.
class PointGrid {
 public:
  explicit PointGrid(double cell) : grid_(cell) {}
  void add(const Vec3& p) { grid_.add(p, p); }
  bool near(const Vec3& p, double radius) const {
    return grid_.any_near(p, [&](const Vec3& q) { return glm::length(p - q) < radius; });
  }

 private:
  CellGrid<Vec3> grid_;
};

// The triangulation of sphere_points(spacing), made once per spacing in the process: every crowded hub at one
// tolerance level looks for its creases on the same fine grid, and its hull was most of a template's time. (A
// handful of spacings in practice, one per tolerance level used.)
const std::vector<Triangle>& fine_triangulation(double spacing) {
  static std::mutex mutex;
  static std::map<double, std::unique_ptr<const std::vector<Triangle>>> made;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& slot = made[spacing];
  if (!slot) slot = std::make_unique<const std::vector<Triangle>>(sphere_triangulation(sphere_points(spacing)));
  return *slot;
}

// The crease curves between the pieces, as points on the direction sphere: crossings of the piece boundaries along
// the edges of a fine triangulation (spacing `fine`), and the triple points where three pieces meet. Directions in a
// collar's cone (cos of the angle to axis k above cos_limit[k]) are left out: nothing meets there.
std::vector<Vec3> crease_points(const RadialHub& hub, const std::vector<Vec3>& axes, const std::vector<double>& cos_limit,
                                double fine, std::vector<Vec3>& triple_points) {
  const std::vector<Vec3> grid = sphere_points(fine);
  std::vector<int> piece(grid.size());
  constexpr int kHole = -2;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    piece[i] = hub.piece(grid[i]);
    for (std::size_t k = 0; k < axes.size(); ++k)
      if (glm::dot(grid[i], axes[k]) > cos_limit[k]) piece[i] = kHole;
  }
  std::vector<Vec3> creases;
  std::unordered_map<std::uint64_t, Vec3> on_edge;  // edge (smaller << 32 | larger) -> its crossing
  for (const Triangle& t : fine_triangulation(fine)) {
    if (piece[t[0]] == kHole || piece[t[1]] == kHole || piece[t[2]] == kHole) continue;
    if (piece[t[0]] == piece[t[1]] && piece[t[1]] == piece[t[2]]) continue;
    Vec3 sum(0.0);
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = t[e], b = t[(e + 1) % 3];
      if (piece[a] == piece[b]) continue;
      const std::uint64_t key = static_cast<std::uint64_t>(std::min(a, b)) << 32 | std::max(a, b);
      auto it = on_edge.find(key);
      if (it == on_edge.end()) {
        it = on_edge.emplace(key, crease_on_arc(hub, grid[a], grid[b], piece[a])).first;
        creases.push_back(it->second);
      }
      sum += it->second;
    }
    if (piece[t[0]] != piece[t[1]] && piece[t[1]] != piece[t[2]] && piece[t[0]] != piece[t[2]])
      triple_points.push_back(triple_point(hub, glm::normalize(sum), {piece[t[0]], piece[t[1]], piece[t[2]]}, fine));
  }
  return creases;
}

// Refinement rounds at most: each round splits every triangle still beyond the tolerance, which divides its error
// by about four, so a handful suffices from the even start.
constexpr int kRefinementRounds = 12;

// Triangulates the directions and refines the triangulation until every triangle lies within `tolerance` of the
// surface it stands for. The surface point along direction w is radius(w) w (ring points: their exact position);
// a triangle's error is measured at its centroid and edge midpoints: the distance from the surface point along
// the sample's direction to the triangle's plane, and, where the sample point itself lies outside the surface
// (outside(p) > 0: a chord across a concave crease), its distance to the surface. The worst sample of every
// triangle beyond the tolerance becomes a new direction, and the directions are triangulated again. Directions for
// which in_hole(w) holds (a cap or a collar's cone, whose polygon is dropped) are never added.
template <class Radius, class Outside, class InHole>
std::vector<Triangle> refined_triangulation(std::vector<Vec3>& directions, std::vector<int>& ring_of,
                                            const std::vector<std::vector<std::uint32_t>>& rings,
                                            const std::vector<Vec3>& ring_points, const Radius& radius,
                                            const Outside& outside, const InHole& in_hole, double tolerance) {
  std::vector<Vec3> position;
  SphereHull hull(directions);
  // Triangles found within the tolerance in an earlier round: the same corners give the same samples, so a
  // triangle that stays from round to round is measured once.
  struct TriangleHash {
    std::size_t operator()(const Triangle& t) const {
      return (static_cast<std::size_t>(t[0]) * 0x9E3779B97F4A7C15ULL ^ t[1]) * 0x9E3779B97F4A7C15ULL ^ t[2];
    }
  };
  std::unordered_set<Triangle, TriangleHash> within;
  for (int round = 0;; ++round) {
    for (std::size_t i = position.size(); i < directions.size(); ++i)
      position.push_back(ring_of[i] >= 0 ? ring_points[i] : radius(directions[i]) * directions[i]);
    std::vector<Triangle> triangles = without_ring_caps(hull.triangles(), ring_of, rings);
    if (round == kRefinementRounds) return triangles;
    // new direction -> it, and a corner of the triangle it refines (where the hull's search starts)
    std::map<std::array<double, 3>, std::pair<Vec3, std::uint32_t>> added;
    for (const Triangle& t : triangles) {
      if (within.count(t)) continue;
      const Vec3 &q0 = position[t[0]], &q1 = position[t[1]], &q2 = position[t[2]];
      const Vec3 normal = glm::cross(q1 - q0, q2 - q0);
      const double area2 = glm::length(normal);
      if (!(area2 > 0.0)) continue;
      double worst = tolerance;
      Vec3 at(0.0);
      const std::array<Vec3, 4> samples{(q0 + q1 + q2) / 3.0, 0.5 * (q0 + q1), 0.5 * (q1 + q2), 0.5 * (q2 + q0)};
      for (const Vec3& point : samples) {
        // The sample's direction from its point (not from the sum of the corners' directions, which names the same
        // direction to within rounding when the corners lie on the sphere): an edge's two triangles then propose
        // exactly the same new direction, never two a rounding apart, which the hull would not both keep.
        const Vec3 w = glm::normalize(point);
        if (in_hole(w)) continue;
        const double error = std::max(std::abs(glm::dot(radius(w) * w - q0, normal)) / area2, outside(point));
        if (error > worst) worst = error, at = w;
      }
      if (worst > tolerance) added.emplace(std::array<double, 3>{at.x, at.y, at.z}, std::make_pair(at, t[0]));
      else within.insert(t);
    }
    if (added.empty()) return triangles;
    for (const auto& [key, refined] : added) {
      const auto& [w, corner] = refined;
      hull.add(w, corner);
      directions.push_back(w);
      ring_of.push_back(-1);
    }
  }
}

}  // namespace

int tolerance_level(double relative_tolerance) {
  return std::max(0, static_cast<int>(std::ceil(-2.0 * std::log2(relative_tolerance) - 1e-9)));
}

double level_tolerance(int level) { return std::exp2(-0.5 * level); }

double sphere_point_count(double tolerance) {
  const double spacing = point_spacing(tolerance);
  return 8.0 * M_PI / (std::sqrt(3.0) * spacing * spacing);  // as sphere_points_at, in double: no overflow
}

int circle_segments(double radius, double tolerance) {
  int n = 6;
  if (tolerance < radius) n = std::max(n, static_cast<int>(std::ceil(M_PI / std::acos(1.0 - tolerance / radius))));
  return std::max(n, static_cast<int>(std::ceil(2.0 * M_PI * radius / point_spacing(tolerance))));
}

HubTemplate tessellate_clean_hub(const std::vector<SphereCap>& caps, double tolerance) {
  const double spacing = point_spacing(tolerance);
  HubTemplate out;
  std::vector<int> ring_of;
  for (std::size_t k = 0; k < caps.size(); ++k) {
    const double rho = std::sqrt((1.0 - caps[k].exit) * (1.0 + caps[k].exit));
    const std::vector<Vec3> ring = circle_points(caps[k].direction, caps[k].exit, rho, circle_segments(rho, tolerance));
    std::vector<std::uint32_t> loop;
    for (const Vec3& p : ring) {
      loop.push_back(static_cast<std::uint32_t>(out.vertices.size()));
      out.vertices.push_back(p);
      ring_of.push_back(static_cast<int>(k));
    }
    out.loops.push_back(std::move(loop));
    out.loop_position.push_back(caps[k].exit);
    out.loop_radius.push_back(rho);
  }
  // Sphere points clear of every cap by about half a spacing, so no sliver forms along a circle (compared as
  // cosines: the angle to the cap's axis above the cap's angle plus half a spacing).
  std::vector<double> cos_clear;
  for (const SphereCap& c : caps)
    cos_clear.push_back(std::cos(std::min(M_PI, std::acos(std::clamp(c.exit, -1.0, 1.0)) + 0.5 * spacing)));
  for (const Vec3& p : sphere_points(spacing)) {
    bool clear = true;
    for (std::size_t k = 0; k < caps.size() && clear; ++k) clear = glm::dot(p, caps[k].direction) < cos_clear[k];
    if (clear) {
      out.vertices.push_back(p);
      ring_of.push_back(-1);
    }
  }
  auto in_cap = [&](const Vec3& w) {
    for (const SphereCap& c : caps)
      if (glm::dot(w, c.direction) >= c.exit) return true;
    return false;
  };
  // Every chord of the sphere and its rings lies inside the ball: nothing outside to measure.
  out.triangles = refined_triangulation(out.vertices, ring_of, out.loops, out.vertices,
                                        [](const Vec3&) { return 1.0; }, [](const Vec3&) { return 0.0; }, in_cap,
                                        tolerance);
  return out;
}

// Collar rings start an eighth of a step past their reference perpendicular. Reference perpendiculars come from
// the coordinate axes, so on a ring starting there points lie in the planes through the beam's axis and a
// coordinate axis: in symmetric lattices, mirror planes, where the crease points and rings of neighbouring hubs
// lie too. Where a short beam's hubs are united (mesh_groups.cpp), such points met within a float's resolution
// and the union folded once rounded (the FCC with beams as thick as its nodes).
constexpr double kCollarRingPhase = 0.125;

HubTemplate tessellate_crowded_hub(const std::vector<CoreStump>& stumps, const std::vector<double>& collars,
                                   double tolerance) {
  const RadialHub hub(stumps, collars);
  // Directions start evenly spaced as on a clean hub; refinement adds them where the stumps curve more.
  std::vector<Vec3> axes;
  std::vector<double> collar_angle;
  for (std::size_t k = 0; k < stumps.size(); ++k) {
    axes.push_back(glm::normalize(stumps[k].direction));
    collar_angle.push_back(std::atan2(stumps[k].radius_at(collars[k]), collars[k]));
  }
  const double spacing = point_spacing(tolerance);
  HubTemplate out;
  std::vector<Vec3> directions;
  std::vector<int> ring_of;
  // The collar rings: exact points of the collar circles, and their directions.
  std::vector<Vec3> ring_points;
  for (std::size_t k = 0; k < stumps.size(); ++k) {
    const double rc = stumps[k].radius_at(collars[k]);
    const int n = std::max(circle_segments(rc, tolerance),
                           static_cast<int>(std::ceil(2.0 * M_PI * std::sin(collar_angle[k]) / spacing)));
    std::vector<std::uint32_t> loop;
    for (const Vec3& p : circle_points(axes[k], collars[k], rc, n, kCollarRingPhase)) {
      loop.push_back(static_cast<std::uint32_t>(directions.size()));
      directions.push_back(glm::normalize(p));
      ring_points.push_back(p);
      ring_of.push_back(static_cast<int>(k));
    }
    out.loops.push_back(std::move(loop));
    out.loop_position.push_back(collars[k]);
    out.loop_radius.push_back(rc);
  }
  // The creases, thinned to about half a spacing (triple points first), then the even points clear of them and of
  // the collars' cones.
  std::vector<double> cos_limit;
  for (double a : collar_angle) cos_limit.push_back(std::cos(a + 0.25 * spacing));
  std::vector<Vec3> triples;
  std::vector<Vec3> creases = crease_points(hub, axes, cos_limit, 0.25 * spacing, triples);
  // Thinned in a fixed order, so the template does not depend on the order the creases were found in.
  auto lexicographic = [](const Vec3& a, const Vec3& b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); };
  std::sort(creases.begin(), creases.end(), lexicographic);
  std::sort(triples.begin(), triples.end(), lexicographic);
  PointGrid kept(0.5 * spacing), dense(0.5 * spacing);
  for (const Vec3& p : creases) dense.add(p);
  for (const Vec3& p : triples) dense.add(p);
  auto keep = [&](const Vec3& p) {
    if (kept.near(p, 0.45 * spacing)) return;
    kept.add(p);
    directions.push_back(p);
    ring_of.push_back(-1);
  };
  for (const Vec3& p : triples) keep(p);
  for (const Vec3& p : creases) keep(p);
  std::vector<double> cos_clear, cos_collar;  // angles to the axes compared as cosines
  for (double a : collar_angle) {
    cos_clear.push_back(std::cos(std::min(M_PI, a + 0.5 * spacing)));
    cos_collar.push_back(std::cos(a));
  }
  for (const Vec3& p : sphere_points(spacing)) {
    bool clear = !dense.near(p, 0.5 * spacing);
    for (std::size_t k = 0; k < axes.size() && clear; ++k) clear = glm::dot(p, axes[k]) < cos_clear[k];
    if (clear) {
      directions.push_back(p);
      ring_of.push_back(-1);
    }
  }
  auto in_collar = [&](const Vec3& w) {
    for (std::size_t k = 0; k < axes.size(); ++k)
      if (glm::dot(w, axes[k]) >= cos_collar[k]) return true;
    return false;
  };
  ring_points.resize(directions.size());
  out.triangles = refined_triangulation(directions, ring_of, out.loops, ring_points,
                                        [&](const Vec3& w) { return hub.radius(w); },
                                        [&](const Vec3& p) { return hub.outside(p); }, in_collar, tolerance);
  // Each direction to its point on the boundary: the radial image of a sphere triangulation is embedded (every
  // triangle keeps its own cone of directions), closed but for the collar holes, and outward.
  out.vertices.resize(directions.size());
  for (std::size_t i = 0; i < directions.size(); ++i)
    out.vertices[i] = ring_of[i] >= 0 ? ring_points[i] : hub.radius(directions[i]) * directions[i];
  return out;
}

}  // namespace steady
