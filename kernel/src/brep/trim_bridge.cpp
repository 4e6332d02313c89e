// The trim policy Bridge: the bridged lattice (steady/brep/bridges.hpp), trimmed with policy Clip.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "brep/trim_phases.hpp"
#include "steady/brep/bridges.hpp"
#include "steady/core/errors.hpp"
#include "steady/query/clean_check.hpp"

namespace steady {

namespace {

using namespace trim;

// How far the far node lies past the wall, in bridge radii beyond its own radius: clear of a convex wall by half a
// radius, so the wall cuts the beam and not the node (at a concave wall part of the node may stay inside it).
constexpr double kFarNodeClearance = 0.5;
// Nearest points farther apart than this (relative to the body's size) make a hub's bridge ambiguous.
constexpr double kAmbiguousRelative = 1e-6;
// The probe for a node on the medial axis (BRepExtrema may report one point of a whole circle of them): the node
// moved straight away from its nearest point by this fraction of the distance. Such a move keeps that point
// nearest unless it crosses the medial axis, where the nearest point jumps to another branch (nodes within this
// fraction of their distance from the medial axis count as on it).
constexpr double kProbeStep = 1e-3;

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

// The least distance between segments [a0, a1] and [b0, b1]: the minimum over the interior critical point (when
// the lines are not parallel and it falls inside both) and the four endpoint-to-segment distances.
double segment_distance(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
  double best = std::min({point_segment_distance(a0, b0, b1), point_segment_distance(a1, b0, b1),
                          point_segment_distance(b0, a0, a1), point_segment_distance(b1, a0, a1)});
  const Vec3 u = a1 - a0, v = b1 - b0, w = a0 - b0;
  const double uu = glm::dot(u, u), uv = glm::dot(u, v), vv = glm::dot(v, v), uw = glm::dot(u, w), vw = glm::dot(v, w);
  const double det = uu * vv - uv * uv;
  if (det > 1e-12 * uu * vv) {
    const double s = (uv * vw - vv * uw) / det, t = (uu * vw - uv * uw) / det;
    if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) best = std::min(best, glm::length(w + s * u - t * v));
  }
  return best;
}

// Whether the bridge (segment from `from` to its far node, radius r) meets a kept element not of hub `hub`: every
// element inside its capsule of its largest radius (a beam is the hull of its end balls, inside that capsule).
bool meets_foreign_element(const FlatLattice& f, const std::vector<char>& kept, std::int64_t hub, const Vec3& from,
                           const Vec3& to, double r, double gap) {
  for (std::int64_t k = 0; k < f.ball_count(); ++k) {
    if (!kept[k] || k == hub) continue;
    if (point_segment_distance(f.balls[k].center, from, to) < f.balls[k].radius + r + gap) return true;
  }
  for (const FlatBeam& b : f.beams) {
    if (!kept[b.a] || !kept[b.b] || b.a == hub || b.b == hub) continue;
    if (segment_distance(from, to, f.balls[b.a].center, f.balls[b.b].center) < std::max(b.ra, b.rb) + r + gap)
      return true;
  }
  return false;
}

}  // namespace

BridgePlan plan_bridges(const FlatLattice& f, const TopoDS_Shape& body_shape, double skin, Progress& progress) {
  // The classification's share of the units (TrimBudget's fixed shares), then the nearest points.
  progress.set_total(100);
  Progress classification(progress, 80);
  TrimBudget budget(classification);
  TrimOptions options;
  options.skin = skin;
  const Bodies bodies = make_bodies(body_shape, options, budget);
  std::vector<BeamFrustum> frustums = beam_frustums(f);
  place_cuts_between_collars(f, frustums);
  const std::vector<char> absorbed = absorbed_balls(f, frustums);
  TrimStats stats;
  const HubStates states = classify(f, frustums, absorbed, bodies, stats, budget);
  const SolidBody& wall = bodies.inner ? *bodies.inner : bodies.body;
  classification.finish();

  BridgePlan plan;
  const std::int64_t n = f.ball_count();
  std::vector<char> kept(n, 0);
  const trim::HubCounts counts = trim::count_hubs(states);
  plan.inside_hubs = counts.inside;
  plan.outside_hubs = counts.outside;
  plan.crossing_hubs = counts.crossing;
  for (std::int64_t i = 0; i < n; ++i)
    kept[i] = states.outer[i] == HubState::Inside && states.inner[i] == HubState::Inside;
  if (std::none_of(kept.begin(), kept.end(), [](char c) { return c; }))
    fail_input("policy", std::string("'bridge' keeps only hubs entirely inside the ") +
                             (bodies.inner ? "skin's inner wall" : "body") + ", and none is: nothing to bridge");

  // The radius of each kept hub's bridge: the largest end radius at it of the beams it lost (0: it lost none).
  std::vector<double> bridge_radius(n, 0.0);
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!frustums[e].exists) continue;
    const FlatBeam& b = f.beams[e];
    if (kept[b.a] && !kept[b.b]) bridge_radius[b.a] = std::max(bridge_radius[b.a], b.ra);
    if (kept[b.b] && !kept[b.a]) bridge_radius[b.b] = std::max(bridge_radius[b.b], b.rb);
  }
  // Nearest points (BRepExtrema: serial).
  const double gap = kClearanceRelative * wall.size();
  std::vector<Bridge> candidates;
  Progress nearest(progress, 20, std::max<std::int64_t>(1, n));
  for (std::int64_t i = 0; i < n; ++i) {
    nearest.advance();
    if (bridge_radius[i] <= 0.0) continue;
    ++plan.lost_neighbour_hubs;
    const Vec3 c = f.balls[i].center;
    const std::vector<Vec3> nearest = wall.nearest_points(c);
    Bridge b;
    b.hub = i;
    b.wall = nearest.front();
    b.radius = bridge_radius[i];
    for (const Vec3& q : nearest)
      b.ambiguous = b.ambiguous || glm::length(q - b.wall) > kAmbiguousRelative * wall.size();
    const double d = glm::length(b.wall - c);  // > the ball's radius: the hub is whole inside
    if (!b.ambiguous) {
      const Vec3 probe = c - (b.wall - c) * kProbeStep;
      const Vec3 moved = wall.nearest_points(probe).front();
      b.ambiguous = glm::length(moved - b.wall) > 100.0 * kProbeStep * d;
    }
    b.end = b.wall + (b.wall - c) / d * ((1.0 + kFarNodeClearance) * b.radius);
    candidates.push_back(b);
  }
  // Bridges that would meet a kept element of another hub are refused; then, in hub order, those meeting an
  // earlier bridge.
  std::vector<char> blocked(candidates.size(), 0);
  tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t k) {
    const Bridge& b = candidates[k];
    blocked[k] = meets_foreign_element(f, kept, b.hub, f.balls[b.hub].center, b.end, b.radius, gap);
  });
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (blocked[k]) {
      plan.blocked.push_back(candidates[k].hub);
      continue;
    }
    const Bridge& b = candidates[k];
    for (const Bridge& earlier : plan.bridges)
      if (segment_distance(f.balls[b.hub].center, b.end, f.balls[earlier.hub].center, earlier.end) <
          b.radius + earlier.radius + gap) {
        blocked[k] = 1;
        break;
      }
    if (blocked[k])
      plan.blocked.push_back(b.hub);
    else
      plan.bridges.push_back(b);
  }
  // The bridged lattice.
  std::vector<std::int64_t> index(n, -1);
  std::vector<Ball> balls;
  for (std::int64_t i = 0; i < n; ++i)
    if (kept[i]) {
      index[i] = static_cast<std::int64_t>(balls.size());
      plan.kept.push_back(i);
      balls.push_back(f.balls[i]);
    }
  std::vector<FlatBeam> beams;
  for (const FlatBeam& b : f.beams)
    if (kept[b.a] && kept[b.b]) beams.push_back({index[b.a], index[b.b], b.ra, b.rb});
  for (const Bridge& b : plan.bridges) {
    beams.push_back({index[b.hub], static_cast<std::int64_t>(balls.size()), b.radius, b.radius});
    balls.push_back({b.end, b.radius});
  }
  plan.lattice = make_flat_lattice(std::move(balls), std::move(beams));
  progress.finish();
  return plan;
}

namespace trim {

TrimResult trim_with_bridges(const FlatLattice& f, const TopoDS_Shape& body, const TrimOptions& options,
                             Progress& progress) {
  progress.set_total(100);
  BridgePlan plan;
  {
    Progress part(progress, 10);
    plan = plan_bridges(f, body, options.skin, part);
  }
  for (std::int64_t hub : plan.blocked)
    report(options, "trim: no bridge from hub " + std::to_string(hub) + ": it would meet another kept element");
  TrimOptions clip = options;
  clip.policy = TrimPolicy::Clip;
  clip.dangling = DanglingBeams::Keep;  // a bridge whose far node is dropped whole is still cut at the wall
  TrimResult out;
  {
    Progress part(progress, 90);
    out = trim_lattice(plan.lattice, body, clip, part);
  }
  TrimStats& s = out.stats;
  s.inside_hubs = plan.inside_hubs;
  s.outside_hubs = plan.outside_hubs;
  s.crossing_hubs = plan.crossing_hubs;
  s.kept_hubs = static_cast<std::int64_t>(plan.kept.size());
  s.lost_neighbour_hubs = plan.lost_neighbour_hubs;
  s.bridges = static_cast<std::int64_t>(plan.bridges.size());
  s.blocked_bridges = static_cast<std::int64_t>(plan.blocked.size());
  s.ambiguous_bridges =
      std::count_if(plan.bridges.begin(), plan.bridges.end(), [](const Bridge& b) { return b.ambiguous; });
  progress.finish();
  return out;
}

}  // namespace trim
}  // namespace steady
