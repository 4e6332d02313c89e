#include "steady/lattice/connector_plan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <array>
#include <map>
#include <sstream>
#include <unordered_map>

#include "lattice/direction_sets.hpp"
#include "steady/core/errors.hpp"
#include "core/cell_grid.hpp"
#include "core/segment_distance.hpp"

namespace steady {

namespace {

// A reach this close to a limit (relative) counts as reaching it: the connectors would touch, or a sleeve end
// exactly where its rod does.
constexpr double kReachMargin = 1e-9;
// Rod lengths are grouped to this many rod radii when the caller gives no length tolerance.
constexpr double kDefaultLengthTolerance = 1e-9;
// The core bulge's range: below 1 % the spheres meet the cylinders at under 8 degrees (near tangent again); above
// 50 % the core is a knob rather than a joint.
constexpr double kMinCoreBulge = 0.01, kMaxCoreBulge = 0.5;
// The largest angle tolerance accepted: beyond it, "congruent" would no longer mean anything for a part.
constexpr double kMaxAngleTolerance = 0.01;

std::string num(double x) {
  std::ostringstream os;
  os.precision(6);
  os << x;
  return os.str();
}

// Unit directions of the beams at `ball`, in incidence order.
std::vector<Vec3> beam_directions(const FlatLattice& f, std::int64_t ball) {
  std::vector<Vec3> out;
  for (const std::int64_t* e = f.incident_begin(ball); e != f.incident_end(ball); ++e) {
    const Vec3 d = f.balls[f.other_ball(*e, ball)].center - f.balls[ball].center;
    const double length = glm::length(d);
    if (!(length > 0.0))
      fail_input("lattice", "beam " + std::to_string(*e) + " joins balls " + std::to_string(f.beams[*e].a) + " and " +
                                std::to_string(f.beams[*e].b) + ", which have the same center: it has no direction");
    out.push_back(d / length);
  }
  return out;
}

// Groups the nodes into families of congruent connectors (their direction sets up to a rotation).
void find_families(const FlatLattice& f, const std::vector<std::vector<Vec3>>& directions, ConnectorPlan& plan) {
  const double tol = plan.parameters.angle_tolerance;
  // Per degree, families by the sum of their pairwise dot products (a rotation invariant), to match few of them.
  std::map<std::size_t, std::multimap<double, int>> by_invariant;
  std::vector<int> second_of_family;
  plan.family_of_ball.assign(f.balls.size(), -1);
  plan.member_of_ball.assign(f.balls.size(), -1);
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    const std::vector<Vec3>& d = directions[i];
    if (d.empty()) {
      ++plan.isolated_balls;
      continue;
    }
    const double sum = pairwise_dot_sum(d);
    const double window = 2.0 * static_cast<double>(d.size() * d.size()) * tol + 1e-12;
    auto& candidates = by_invariant[d.size()];
    int family = -1;
    Mat3 rotation(1.0);
    for (auto it = candidates.lower_bound(sum - window); it != candidates.end() && it->first <= sum + window; ++it)
      if (match_direction_set(plan.families[it->second].directions, second_of_family[it->second], d, tol, rotation)) {
        family = it->second;
        break;
      }
    if (family < 0) {
      const DirectionFrame frame = direction_frame(d);
      ConnectorFamily fam;
      for (const Vec3& w : d) fam.directions.push_back(glm::transpose(frame.rotation) * w);
      family = static_cast<int>(plan.families.size());
      plan.families.push_back(std::move(fam));
      second_of_family.push_back(frame.second);
      candidates.emplace(sum, family);
      rotation = frame.rotation;
    }
    plan.family_of_ball[i] = family;
    plan.member_of_ball[i] = static_cast<int>(plan.families[family].members.size());
    plan.families[family].members.push_back({i, rotation, f.balls[i].center});
  }
}

// Where the reach range of a lattice comes from: the node whose rods end deepest, the beam that allows least.
struct ReachLimits {
  double min_reach = 0.0, max_reach = 0.0;
  std::int64_t gripping_ball = -1, shortest_beam = -1;
  double deepest = 0.0;  // rod radii
};

ReachLimits reach_limits(const FlatLattice& f, const std::vector<std::vector<double>>& depths,
                         const ConnectorParameters& p) {
  ReachLimits r;
  r.min_reach = p.sleeve * (1.0 + p.core_bulge);
  for (std::int64_t i = 0; i < f.ball_count(); ++i)
    for (std::size_t s = 0; s < depths[i].size(); ++s) {
      const double t = depths[i][s] / p.rod_radius;
      const double needed = std::sqrt(t * t + p.sleeve * p.sleeve);
      if (needed > r.min_reach) r.min_reach = needed, r.gripping_ball = i, r.deepest = t;
    }
  r.max_reach = std::numeric_limits<double>::infinity();
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    const double length = glm::length(f.balls[f.beams[e].b].center - f.balls[f.beams[e].a].center) / p.rod_radius;
    // Apart: each connector's sleeve runs sqrt(reach^2 - hole^2) along the beam, at most half of it. Exact
    // template: the beam's far end lies outside the connector's ball.
    const double fits = std::min(length, std::sqrt(0.25 * length * length + p.hole * p.hole));
    if (fits < r.max_reach) r.max_reach = fits, r.shortest_beam = e;
  }
  return r;
}

// Throws naming "reach" when the parameters' reach is outside the lattice's range.
void check_reach(const FlatLattice& f, const ReachLimits& r, const ConnectorParameters& p) {
  const std::string range = r.min_reach < r.max_reach
                                ? "reaches in (" + num(r.min_reach) + ", " + num(r.max_reach) + ") fit this lattice"
                                : "no reach fits this lattice with this sleeve and hole (rods end too deep, or beams are "
                                  "too short): use a thinner rod or sleeve";
  if (p.reach <= r.min_reach * (1.0 + kReachMargin)) {
    if (r.gripping_ball < 0)
      fail_input("reach", "must be > sleeve (1 + core_bulge) (got " + num(p.reach) + " <= " + num(r.min_reach) + ")");
    fail_input("reach", num(p.reach) + " is too small to hold the rods at ball " + std::to_string(r.gripping_ball) +
                            ": a rod ends " + num(r.deepest) + " rod radii from its center (where it would meet another "
                            "rod), beyond the sleeve's full wall (sqrt(reach^2 - sleeve^2) = " +
                            num(std::sqrt(std::max(0.0, p.reach * p.reach - p.sleeve * p.sleeve))) + "); " + range);
  }
  if (p.reach >= r.max_reach * (1.0 - kReachMargin)) {
    const FlatBeam& b = f.beams[r.shortest_beam];
    const double length = glm::length(f.balls[b.b].center - f.balls[b.a].center);
    fail_input("reach", "beam " + std::to_string(r.shortest_beam) + " (balls " + std::to_string(b.a) + " and " +
                            std::to_string(b.b) + ", length " + num(length) +
                            ") is too short to separate its two connectors at reach " + num(p.reach) +
                            ": the largest reach that fits it is " + num(r.max_reach) + " rod radii; " + range);
  }
}

// Unit beam directions per ball and the depths where their rods end; throws naming "lattice" for a beam without
// direction or two rods of a node on one line.
void node_directions(const FlatLattice& f, double rod_radius, std::vector<std::vector<Vec3>>& directions,
                     std::vector<std::vector<double>>& depths) {
  directions.assign(f.balls.size(), {});
  depths.assign(f.balls.size(), {});
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    directions[i] = beam_directions(f, i);
    for (std::size_t s = 0; s < directions[i].size(); ++s) {
      depths[i].push_back(rod_end_depth(directions[i], s, rod_radius));
      if (!std::isfinite(depths[i].back()))
        fail_input("lattice", "ball " + std::to_string(i) + " has two beams leaving it in the same direction (beam " +
                                  std::to_string(f.incident_begin(i)[s]) + " and another): their rods would overlap");
    }
  }
}

void make_rods(const FlatLattice& f, const std::vector<std::vector<double>>& depths, ConnectorPlan& plan) {
  const ConnectorParameters& p = plan.parameters;
  const double sleeve_end = std::sqrt(p.reach * p.reach - p.hole * p.hole) * p.rod_radius;
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    Rod r;
    r.beam = e, r.a = f.beams[e].a, r.b = f.beams[e].b;
    const Vec3 a = f.balls[r.a].center, b = f.balls[r.b].center;
    const double length = glm::length(b - a);
    const Vec3 axis = (b - a) / length;
    r.depth_a = depths[r.a][f.incident_slot(r.a, e)];
    r.depth_b = depths[r.b][f.incident_slot(r.b, e)];
    r.start = a + r.depth_a * axis;
    r.end = b - r.depth_b * axis;
    r.length = length - r.depth_a - r.depth_b;
    r.exposed = length - 2.0 * sleeve_end;
    plan.rods.push_back(r);
  }
  const double tol = p.length_tolerance > 0.0 ? p.length_tolerance : kDefaultLengthTolerance * p.rod_radius;
  std::vector<std::int64_t> order(plan.rods.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<std::int64_t>(k);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::int64_t x, std::int64_t y) { return plan.rods[x].length < plan.rods[y].length; });
  for (std::int64_t k : order) {
    const double length = plan.rods[k].length;
    if (plan.cut_list.empty() || length - plan.rods[plan.cut_list.back().rods.front()].length > tol)
      plan.cut_list.push_back({length, {}});
    plan.cut_list.back().length = length;
    plan.cut_list.back().rods.push_back(k);
  }
}


// A ball or capsule (the points within `radius` of the segment [a, b]; a ball when a == b): the convex pieces the
// clash tests intersect.
struct ConvexPiece {
  Vec3 a, b;
  double radius;
};

// Whether the pieces have a common point (to within `slack`): cyclic projections onto closed convex sets converge to
// a point of their intersection when it is not empty, and keep a gap when it is. A contact closer than `slack`, or
// so grazing that 1,000 rounds do not settle it, counts as none.
bool pieces_meet(const std::vector<ConvexPiece>& pieces, double slack) {
  Vec3 p(0.0);
  for (const ConvexPiece& s : pieces) p += 0.5 * (s.a + s.b);
  p /= static_cast<double>(pieces.size());
  for (int round = 0; round < 1000; ++round) {
    for (const ConvexPiece& s : pieces) {
      const Vec3 ab = s.b - s.a;
      const double len2 = glm::dot(ab, ab);
      const Vec3 q = s.a + (len2 > 0.0 ? std::clamp(glm::dot(p - s.a, ab) / len2, 0.0, 1.0) : 0.0) * ab;
      const double d = glm::length(p - q);
      if (d > s.radius) p = q + (s.radius / d) * (p - q);
    }
    double worst = 0.0;
    for (const ConvexPiece& s : pieces) worst = std::max(worst, point_segment_distance(p, s.a, s.b) - s.radius);
    if (worst <= slack) return true;
  }
  return false;
}

// The space a connector takes, for the clash tests: its core ball, and per arm the material between the hole and
// the sleeve within the reach, which lies in the sleeve's capsule about the axis out to sqrt(reach^2 - hole^2) (the
// farthest it goes along the axis) intersected with the reach ball. Each is convex; a clash is a common point.
struct ConnectorSpace {
  const FlatLattice& f;
  const std::vector<std::vector<Vec3>>& directions;
  double rho, reach, sleeve, core, arm;
  ConnectorSpace(const FlatLattice& lattice, const std::vector<std::vector<Vec3>>& d, const ConnectorParameters& p,
                 double reach_radii)
      : f(lattice), directions(d), rho(p.rod_radius), reach(reach_radii * p.rod_radius),
        sleeve(p.sleeve * p.rod_radius), core(p.sleeve * (1.0 + p.core_bulge) * p.rod_radius),
        arm(std::sqrt(reach_radii * reach_radii - p.hole * p.hole) * p.rod_radius) {}

  ConvexPiece reach_ball(std::int64_t i) const { return {f.balls[i].center, f.balls[i].center, reach}; }
  ConvexPiece core_ball(std::int64_t i) const { return {f.balls[i].center, f.balls[i].center, core}; }
  ConvexPiece arm_capsule(std::int64_t i, std::size_t slot) const {
    return {f.balls[i].center, f.balls[i].center + arm * directions[i][slot], sleeve};
  }
  bool along(std::int64_t node, std::size_t slot, std::int64_t other) const {
    return f.other_ball(f.incident_begin(node)[slot], node) == other;
  }
  double slack() const { return 1e-6 * rho; }

  // Whether the connector at ball i meets the rod of beam e (not one of its own).
  bool meets_rod(std::int64_t i, const Rod& rod) const {
    const Vec3 c = f.balls[i].center;
    const double gap = point_segment_distance(c, rod.start, rod.end);
    if (gap >= reach + rho) return false;
    if (gap < core + rho) return true;
    const ConvexPiece r{rod.start, rod.end, rho};
    for (std::size_t a = 0; a < directions[i].size(); ++a)
      if (pieces_meet({arm_capsule(i, a), reach_ball(i), r}, slack())) return true;
    return false;
  }
  // Whether the connectors at balls i and j meet, apart from their arms along a beam joining them (the reach range
  // keeps those apart).
  bool meets_connector(std::int64_t i, std::int64_t j) const {
    const double gap = glm::length(f.balls[j].center - f.balls[i].center);
    if (gap >= 2.0 * reach) return false;
    if (gap < 2.0 * core) return true;
    for (std::size_t a = 0; a < directions[i].size(); ++a)
      if (!along(i, a, j) && pieces_meet({arm_capsule(i, a), reach_ball(i), core_ball(j)}, slack())) return true;
    for (std::size_t b = 0; b < directions[j].size(); ++b)
      if (!along(j, b, i) && pieces_meet({arm_capsule(j, b), reach_ball(j), core_ball(i)}, slack())) return true;
    for (std::size_t a = 0; a < directions[i].size(); ++a)
      for (std::size_t b = 0; b < directions[j].size(); ++b)
        if (!along(i, a, j) && !along(j, b, i) &&
            pieces_meet({arm_capsule(i, a), reach_ball(i), arm_capsule(j, b), reach_ball(j)}, slack()))
          return true;
    return false;
  }
};

// The largest reach (rod radii, above `lowest`) at which `clashes(reach)` no longer holds, by bisection (a longer
// reach only lengthens the arms); `lowest` itself when even that clashes.
template <class Clashes>
double largest_clear_reach(double lowest, double reach, Clashes&& clashes) {
  if (clashes(lowest)) return lowest;
  double lo = lowest, hi = reach;
  for (int it = 0; it < 60; ++it) (clashes(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
  return lo;
}

// Throws naming "reach" when a connector may meet a rod that does not end at its node, or another node's connector
// (beside their arms along a beam they share): the parts would not assemble. Names the two and the largest reach
// that clears them. Candidates from a grid of node centers: O(nodes + rods x length / reach).
void check_clashes(const FlatLattice& f, const std::vector<std::vector<Vec3>>& directions, const ConnectorPlan& plan,
                   double min_reach) {
  const ConnectorParameters& p = plan.parameters;
  const ConnectorSpace space(f, directions, p, p.reach);
  // Node centers in cells of twice the reach: a connector's neighbours, and the nodes near a point of a rod, are in
  // the 27 cells about it.
  CellGrid<std::int64_t> grid(2.0 * space.reach);
  for (std::int64_t i = 0; i < f.ball_count(); ++i) grid.add(f.balls[i].center, i);
  const auto fix = [&](double largest) {
    return largest > min_reach ? "; the largest reach that clears them is " + num(largest) + " rod radii"
                               : "; no reach clears them: use a thinner rod or sleeve, or move the nodes apart";
  };
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    if (directions[i].empty()) continue;
    grid.any_near(f.balls[i].center, [&](std::int64_t j) {
      if (j <= i || directions[j].empty() || !space.meets_connector(i, j)) return false;
      const double largest = largest_clear_reach(min_reach, p.reach, [&](double r) {
        return ConnectorSpace(f, directions, p, r).meets_connector(i, j);
      });
      fail_input("reach", "the connectors at balls " + std::to_string(i) + " and " + std::to_string(j) +
                              " would meet (reach " + num(p.reach) + " rod radii)" + fix(largest));
    });
  }
  for (const Rod& rod : plan.rods) {
    // Samples every half reach along the rod: a node within reach + rod radius of it is within 2 reach of one.
    const double length = glm::length(rod.end - rod.start);
    const int samples = static_cast<int>(std::ceil(length / (0.5 * space.reach))) + 1;
    std::vector<std::int64_t> seen;
    for (int s = 0; s < samples; ++s) {
      const Vec3 at = rod.start + (static_cast<double>(s) / std::max(1, samples - 1)) * (rod.end - rod.start);
      grid.any_near(at, [&](std::int64_t i) {
        if (i == rod.a || i == rod.b || directions[i].empty()) return false;
        if (std::find(seen.begin(), seen.end(), i) != seen.end()) return false;
        seen.push_back(i);
        if (!space.meets_rod(i, rod)) return false;
        const double largest = largest_clear_reach(min_reach, p.reach, [&](double r) {
          return ConnectorSpace(f, directions, p, r).meets_rod(i, rod);
        });
        fail_input("reach", "the connector at ball " + std::to_string(i) + " would meet the rod of beam " +
                                std::to_string(rod.beam) + " (balls " + std::to_string(rod.a) + " and " +
                                std::to_string(rod.b) + "), which does not end there (reach " + num(p.reach) +
                                " rod radii)" + fix(largest));
      });
    }
  }
}
}  // namespace

void check_connector_parameters(const ConnectorParameters& p) {
  require_positive(p.rod_radius, "rod_radius");
  require_finite(p.hole, "hole");
  if (!(p.hole >= 1.0)) fail_input("hole", "must be >= 1 rod radius, so that a rod fits (got " + num(p.hole) + ")");
  require_finite(p.sleeve, "sleeve");
  if (!(p.sleeve > p.hole))
    fail_input("sleeve", "must be > hole (" + num(p.hole) + " rod radii), or the sleeves have no wall (got " +
                             num(p.sleeve) + ")");
  require_finite(p.core_bulge, "core_bulge");
  if (!(p.core_bulge >= kMinCoreBulge && p.core_bulge <= kMaxCoreBulge))
    fail_input("core_bulge", "must lie in [" + num(kMinCoreBulge) + ", " + num(kMaxCoreBulge) + "] (got " +
                                 num(p.core_bulge) + ")");
  require_finite(p.reach, "reach");
  if (!(p.reach > p.sleeve * (1.0 + p.core_bulge)))
    fail_input("reach", "must be > sleeve (1 + core_bulge) = " + num(p.sleeve * (1.0 + p.core_bulge)) +
                            " rod radii, or the connector has no arms (got " + num(p.reach) + ")");
  require_finite(p.angle_tolerance, "angle_tolerance");
  if (!(p.angle_tolerance >= 0.0 && p.angle_tolerance <= kMaxAngleTolerance))
    fail_input("angle_tolerance", "must lie in [0, " + num(kMaxAngleTolerance) + "] radians (got " +
                                      num(p.angle_tolerance) + ")");
  require_finite(p.length_tolerance, "length_tolerance");
  if (!(p.length_tolerance >= 0.0))
    fail_input("length_tolerance", "must be >= 0 (got " + num(p.length_tolerance) + ")");
}

double rod_end_depth(const std::vector<Vec3>& directions, std::size_t slot, double rod_radius) {
  double depth = 0.0;
  for (std::size_t k = 0; k < directions.size(); ++k) {
    if (k == slot) continue;
    const Vec3& a = directions[slot];
    const Vec3& b = directions[k];
    const double half = 0.5 * std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
    if (!(half > 0.0)) return std::numeric_limits<double>::infinity();
    depth = std::max(depth, rod_radius * std::cos(half) / std::sin(half));
  }
  return std::max(depth, 0.0);
}

std::pair<double, double> connector_reach_range(const FlatLattice& f, const ConnectorParameters& parameters) {
  ConnectorParameters p = parameters;
  // The reach is what is being asked for: any valid one will do for the checks.
  if (std::isfinite(p.sleeve) && std::isfinite(p.core_bulge)) p.reach = 2.0 * p.sleeve * (1.0 + p.core_bulge) + 1.0;
  check_connector_parameters(p);
  std::vector<std::vector<Vec3>> directions;
  std::vector<std::vector<double>> depths;
  node_directions(f, p.rod_radius, directions, depths);
  const ReachLimits r = reach_limits(f, depths, p);
  return {r.min_reach, r.max_reach};
}

ConnectorPlan plan_connectors(const FlatLattice& f, const ConnectorParameters& parameters) {
  check_connector_parameters(parameters);
  ConnectorPlan plan;
  plan.parameters = parameters;
  std::vector<std::vector<Vec3>> directions;
  std::vector<std::vector<double>> depths;
  node_directions(f, parameters.rod_radius, directions, depths);
  const ReachLimits limits = reach_limits(f, depths, parameters);
  check_reach(f, limits, parameters);
  plan.min_reach = limits.min_reach;
  plan.max_reach = limits.max_reach;
  find_families(f, directions, plan);
  make_rods(f, depths, plan);
  check_clashes(f, directions, plan, limits.min_reach);
  return plan;
}

}  // namespace steady
