// The trim policy Bridge: the bridged lattice (steady/brep/bridges.hpp), trimmed with policy Clip.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <utility>

#include "brep/bridge_routes.hpp"
#include "brep/trim_phases.hpp"
#include "steady/brep/bridges.hpp"
#include "steady/core/errors.hpp"
#include "steady/query/clean_check.hpp"

namespace steady {

namespace {

using namespace trim;

// Nearest points farther apart than this (relative to the body's size) make a hub's bridge ambiguous.
constexpr double kAmbiguousRelative = 1e-6;
// The probe for a node on the medial axis (BRepExtrema may report one point of a whole circle of them): the node
// moved straight away from its nearest point by this fraction of the distance. Such a move keeps that point
// nearest unless it crosses the medial axis, where the nearest point jumps to another branch (nodes within this
// fraction of their distance from the medial axis count as on it).
constexpr double kProbeStep = 1e-3;

// The bridges of `candidates` (toward the nearest points, in hub order) into `plan`: first every one clear of the
// kept elements of other hubs and of the bridges made before it; then, in hub order, the blocked ones rerouted
// (clear of every bridge made so far), or counted blocked when no route is clear. `lost`: (hub, neighbour it
// lost) in hub order.
void choose_bridges(const FlatLattice& f, const SolidBody& wall, const std::vector<char>& kept, double gap,
                    const std::vector<Bridge>& candidates,
                    const std::vector<std::pair<std::int64_t, std::int64_t>>& lost, BridgePlan& plan,
                    Progress& progress) {
  const bridges::Clearance clearance(f, kept, gap);
  std::vector<char> blocked(candidates.size(), 0);
  tbb::parallel_for(std::size_t(0), candidates.size(),
                    [&](std::size_t k) { blocked[k] = clearance.meets_kept_element(candidates[k]); });
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    blocked[k] = blocked[k] || clearance.meets_bridge(candidates[k], plan.bridges);
    if (!blocked[k]) plan.bridges.push_back(candidates[k]);
  }
  const std::int64_t count = std::count(blocked.begin(), blocked.end(), 1);
  progress.set_total(std::max<std::int64_t>(1, count));
  if (count == 0) return;
  bridges::BridgeRouter router(f, wall);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (!blocked[k]) continue;
    progress.advance();
    const Bridge& b = candidates[k];
    const Vec3 c = f.balls[b.hub].center;
    std::vector<Vec3> directions;
    const auto range = std::equal_range(lost.begin(), lost.end(), std::make_pair(b.hub, std::int64_t(0)),
                                        [](const auto& x, const auto& y) { return x.first < y.first; });
    for (auto it = range.first; it != range.second; ++it)
      directions.push_back(glm::normalize(f.balls[it->second].center - c));
    if (const std::optional<Bridge> rerouted = router.reroute(b, directions, clearance, plan.bridges))
      plan.bridges.push_back(*rerouted);
    else
      plan.blocked.push_back(b.hub);
  }
}

}  // namespace

BridgePlan plan_bridges(const FlatLattice& f, const TopoDS_Shape& body_shape, double skin, Progress& progress) {
  // The classification's share of the units (TrimBudget's fixed shares), then the nearest points and the routes.
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
  std::vector<std::pair<std::int64_t, std::int64_t>> lost;  // (kept hub, the neighbour it lost)
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!frustums[e].exists) continue;
    const FlatBeam& b = f.beams[e];
    if (kept[b.a] && !kept[b.b]) {
      bridge_radius[b.a] = std::max(bridge_radius[b.a], b.ra);
      lost.emplace_back(b.a, b.b);
    }
    if (kept[b.b] && !kept[b.a]) {
      bridge_radius[b.b] = std::max(bridge_radius[b.b], b.rb);
      lost.emplace_back(b.b, b.a);
    }
  }
  std::stable_sort(lost.begin(), lost.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  // Nearest points (BRepExtrema: serial).
  std::vector<Bridge> candidates;
  Progress nearest(progress, 15, std::max<std::int64_t>(1, n));
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
    b.end = b.wall + (b.wall - c) / d * ((1.0 + bridges::kFarNodeClearance) * b.radius);
    candidates.push_back(b);
  }
  {
    Progress routes(progress, 5);
    choose_bridges(f, wall, kept, kClearanceRelative * wall.size(), candidates, lost, plan, routes);
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
  for (const Bridge& b : plan.bridges)
    if (b.rerouted)
      report(options, "trim: bridge from hub " + std::to_string(b.hub) +
                          " rerouted: toward its nearest wall point it would meet another kept element");
  for (std::int64_t hub : plan.blocked)
    report(options, "trim: no bridge from hub " + std::to_string(hub) +
                        ": on every route tried (its nearest wall point, the beams it lost, up to " +
                        std::to_string(bridges::kRings * bridges::kRingDirections) +
                        " directions about the nearest) it would meet another kept element");
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
  s.rerouted_bridges =
      std::count_if(plan.bridges.begin(), plan.bridges.end(), [](const Bridge& b) { return b.rerouted; });
  s.blocked_bridges = static_cast<std::int64_t>(plan.blocked.size());
  s.ambiguous_bridges =
      std::count_if(plan.bridges.begin(), plan.bridges.end(), [](const Bridge& b) { return b.ambiguous; });
  progress.finish();
  return out;
}

}  // namespace trim
}  // namespace steady
