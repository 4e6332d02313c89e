// The trim policy Bridge: kept hubs whole inside the wall, one bridge per kept hub that lost a neighbour, the part
// one valid solid whose volume agrees with Monte Carlo membership in (kept hubs u bridges) n wall (u skin), every
// kept ball inside the part, and the decisions for blocked and ambiguous bridges.
#include <gtest/gtest.h>

#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <set>

#include "lattice_membership.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/bridges.hpp"
#include "steady/brep/trim.hpp"
#include "test_lattices.hpp"
#include "steady/core/constants.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/progress.hpp"
#include "steady/cots/becots_lattice.hpp"
#include "steady/cots/becots_map.hpp"
#include "steady/lattice/flat_lattice.hpp"

namespace steady {
namespace {

using test::grid_lattice;

// A body with its wall described independently of OpenCASCADE: membership in the body shrunk by t, the distance
// from an inside point to the wall of the body shrunk by t, the volume of the skin of thickness t.
struct Body {
  const char* name;
  TopoDS_Shape shape;
  Vec3 lo, hi;  // a box around it
  std::function<bool(const Vec3&, double)> inside;
  std::function<double(const Vec3&, double)> distance;
  std::function<double(double)> skin_volume;
};

// The cylinder about the vertical line through (2.5, 2.5), radius 2.4, from z = 0.4 to 4.6.
Body cylinder() {
  const double r = 2.4, z0 = 0.4, z1 = 4.6;
  auto rho = [](const Vec3& p) { return std::hypot(p.x - 2.5, p.y - 2.5); };
  return {"cylinder",
          BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(2.5, 2.5, z0), gp_Dir(0, 0, 1)), r, z1 - z0).Shape(),
          {2.5 - r, 2.5 - r, z0},
          {2.5 + r, 2.5 + r, z1},
          [=](const Vec3& p, double t) { return p.z >= z0 + t && p.z <= z1 - t && rho(p) <= r - t; },
          [=](const Vec3& p, double t) { return std::min({r - t - rho(p), p.z - z0 - t, z1 - t - p.z}); },
          [=](double t) { return kPi * (r * r * (z1 - z0) - (r - t) * (r - t) * (z1 - z0 - 2 * t)); }};
}

// The frustum of a cone about the same line, radius 2.6 at z = 0.4 to 1.4 at z = 4.6 (no skin: no closed form
// for its offset is needed).
Body cone() {
  const double r0 = 2.6, r1 = 1.4, z0 = 0.4, h = 4.2;
  const double slope = (r0 - r1) / h, cos_a = 1.0 / std::hypot(1.0, slope);
  auto rho = [](const Vec3& p) { return std::hypot(p.x - 2.5, p.y - 2.5); };
  auto radius_at = [=](double z) { return r0 - slope * (z - z0); };
  return {"cone",
          BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(2.5, 2.5, z0), gp_Dir(0, 0, 1)), r0, r1, h).Shape(),
          {2.5 - r0, 2.5 - r0, z0},
          {2.5 + r0, 2.5 + r0, z0 + h},
          [=](const Vec3& p, double) { return p.z >= z0 && p.z <= z0 + h && rho(p) <= radius_at(p.z); },
          [=](const Vec3& p, double) {
            return std::min({(radius_at(p.z) - rho(p)) * cos_a, p.z - z0, z0 + h - p.z});
          },
          [](double) { return 0.0; }};
}

bool part_contains(const TopoDS_Shape& part, const Vec3& p) {
  BRepClass3d_SolidClassifier c(part, gp_Pnt(p.x, p.y, p.z), 1e-7);
  return c.State() == TopAbs_IN;
}

// Checks a bridged trim of `f` into `body` with a skin of thickness `skin`: the plan against the body's own
// description, the part against Monte Carlo.
void check_bridged(const FlatLattice& f, const Body& body, double skin, const std::string& what) {
  const BridgePlan plan = plan_bridges(f, body.shape, skin);
  // Kept hubs: balls whole inside the wall.
  std::vector<char> kept(f.ball_count(), 0);
  for (std::int64_t i : plan.kept) {
    kept[i] = 1;
    EXPECT_GT(body.distance(f.balls[i].center, skin), f.balls[i].radius) << what << ": kept hub " << i;
  }
  for (std::int64_t i = 0; i < f.ball_count(); ++i)
    if (body.distance(f.balls[i].center, skin) < f.balls[i].radius) EXPECT_FALSE(kept[i]) << what << ": hub " << i;
  // Hubs that lost a neighbour, and their bridges' radii, counted here from the source lattice.
  std::vector<double> lost(f.ball_count(), 0.0);
  for (const FlatBeam& b : f.beams) {
    if (kept[b.a] && !kept[b.b]) lost[b.a] = std::max(lost[b.a], b.ra);
    if (kept[b.b] && !kept[b.a]) lost[b.b] = std::max(lost[b.b], b.rb);
  }
  const std::int64_t lost_hubs = std::count_if(lost.begin(), lost.end(), [](double r) { return r > 0.0; });
  EXPECT_GT(lost_hubs, 0) << what;
  EXPECT_EQ(plan.lost_neighbour_hubs, lost_hubs) << what;
  EXPECT_TRUE(plan.blocked.empty()) << what;
  EXPECT_EQ(static_cast<std::int64_t>(plan.bridges.size()), lost_hubs) << what;
  std::set<std::int64_t> bridged;
  for (const Bridge& b : plan.bridges) {
    bridged.insert(b.hub);
    const Vec3 c = f.balls[b.hub].center;
    EXPECT_NEAR(glm::length(b.wall - c), body.distance(c, skin), 1e-6) << what << ": bridge of hub " << b.hub;
    EXPECT_NEAR(body.distance(b.wall, skin), 0.0, 1e-6) << what << ": its wall point";
    EXPECT_EQ(b.radius, lost[b.hub]) << what;
    EXPECT_FALSE(b.rerouted) << what;
  }
  EXPECT_EQ(static_cast<std::int64_t>(bridged.size()), lost_hubs) << what << ": a hub bridged twice";

  TrimOptions o;
  o.policy = TrimPolicy::Bridge;
  o.skin = skin;
  const TrimResult r = trim_lattice(f, body.shape, o);
  EXPECT_TRUE(is_valid(r.part)) << what << ":\n" << validity_report(r.part);
  EXPECT_EQ(solid_count(r.part), 1) << what;
  EXPECT_EQ(r.stats.bridges, lost_hubs) << what;
  EXPECT_EQ(r.stats.lost_neighbour_hubs, lost_hubs) << what;
  EXPECT_EQ(r.stats.kept_hubs, static_cast<std::int64_t>(plan.kept.size())) << what;
  EXPECT_EQ(r.stats.blocked_bridges, 0) << what;
  EXPECT_EQ(r.stats.rerouted_bridges, 0) << what;
  // No kept hub is cut: its center and six points at 0.95 of its radius lie inside the part.
  for (std::int64_t i : plan.kept) {
    const Ball& ball = f.balls[i];
    EXPECT_TRUE(part_contains(r.part, ball.center)) << what << ": hub " << i;
    for (int axis = 0; axis < 3; ++axis)
      for (double s : {-0.95, 0.95}) {
        Vec3 p = ball.center;
        p[axis] += s * ball.radius;
        EXPECT_TRUE(part_contains(r.part, p)) << what << ": hub " << i;
      }
  }
  // Monte Carlo: the skin in closed form, plus the bridged lattice inside the wall.
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> ux(body.lo.x, body.hi.x), uy(body.lo.y, body.hi.y), uz(body.lo.z, body.hi.z);
  const int samples = 60000;
  int hits = 0;
  for (int k = 0; k < samples; ++k) {
    const Vec3 p(ux(rng), uy(rng), uz(rng));
    hits += body.inside(p, skin) && test::in_lattice(plan.lattice, p);
  }
  const Vec3 e = body.hi - body.lo;
  const double box_volume = e.x * e.y * e.z, frac = double(hits) / samples;
  const double estimate = frac * box_volume + body.skin_volume(skin);
  const double sigma = std::sqrt(frac * (1 - frac) / samples) * box_volume;
  const double volume = shape_volume(r.part);
  EXPECT_NEAR(volume, estimate, 4 * sigma) << what;
  std::printf("[ bridge   ] %s: %lld kept hubs, %lld bridges (%lld ambiguous), volume %.5f, Monte Carlo %.5f +- %.5f\n",
              what.c_str(), static_cast<long long>(r.stats.kept_hubs), static_cast<long long>(r.stats.bridges),
              static_cast<long long>(r.stats.ambiguous_bridges), volume, estimate, sigma);
}

TEST(TrimBridge, StrutGridInCylinderAndConeAgreesWithMonteCarlo) {
  const FlatLattice f = grid_lattice(6);
  check_bridged(f, cylinder(), 0.0, "grid in cylinder");
  check_bridged(f, cone(), 0.0, "grid in cone");
}

TEST(TrimBridge, StrutGridInCylinderWithSkinAgreesWithMonteCarlo) {
  check_bridged(grid_lattice(6), cylinder(), 0.3, "grid in cylinder, skin 0.3");
}

// A box described independently of OpenCASCADE: the signed distance from a point to its wall (positive inside).
struct TestBox {
  Vec3 lo, hi;
  TopoDS_Shape shape() const {
    return BRepPrimAPI_MakeBox(gp_Pnt(lo.x, lo.y, lo.z), gp_Pnt(hi.x, hi.y, hi.z)).Shape();
  }
  double distance(const Vec3& p) const {
    double inside = std::numeric_limits<double>::infinity(), outside = 0.0;
    for (int k = 0; k < 3; ++k) {
      inside = std::min({inside, p[k] - lo[k], hi[k] - p[k]});
      const double out = std::max({0.0, lo[k] - p[k], p[k] - hi[k]});
      outside += out * out;
    }
    return inside >= 0.0 ? inside : -std::sqrt(outside);
  }
};

// The least clearance between `bridge` (its axis from its hub's node to its far node, radius r) and the kept
// elements of `f` not of its hub, by brute force: both axes sampled at 400 points, each element point with its
// own radius (a beam's linearly interpolated: the hull of its end balls lies inside that union of balls), minus
// the sampling steps (so the result is a lower bound of the true clearance).
double brute_force_clearance(const FlatLattice& f, const std::vector<std::int64_t>& kept, const Bridge& bridge) {
  const int n = 400;
  const std::set<std::int64_t> is_kept(kept.begin(), kept.end());
  const Vec3 from = f.balls[bridge.hub].center;
  const double bridge_step = glm::length(bridge.end - from) / (n - 1);
  auto clearance_to = [&](const Vec3& a, const Vec3& b, double ra, double rb) {
    const double step = glm::length(b - a) / (n - 1) + std::abs(rb - ra) / (n - 1);
    double least = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      const Vec3 p = from + (bridge.end - from) * (double(i) / (n - 1));
      for (int j = 0; j < n; ++j) {
        const double t = double(j) / (n - 1);
        least = std::min(least, glm::length(p - (a + (b - a) * t)) - (ra + (rb - ra) * t) - bridge.radius);
      }
    }
    return least - bridge_step - step;
  };
  double least = std::numeric_limits<double>::infinity();
  for (std::int64_t k : kept)
    if (k != bridge.hub)
      least = std::min(least, clearance_to(f.balls[k].center, f.balls[k].center, f.balls[k].radius,
                                           f.balls[k].radius));
  for (const FlatBeam& b : f.beams)
    if (is_kept.count(b.a) && is_kept.count(b.b) && b.a != bridge.hub && b.b != bridge.hub)
      least = std::min(least, clearance_to(f.balls[b.a].center, f.balls[b.b].center, b.ra, b.rb));
  return least;
}

// Monte Carlo volume of the bridged lattice inside `box`, sampled in [lo, hi]: estimate and sigma.
std::pair<double, double> box_monte_carlo(const FlatLattice& bridged, const TestBox& box, const Vec3& lo,
                                          const Vec3& hi, int samples) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> ux(lo.x, hi.x), uy(lo.y, hi.y), uz(lo.z, hi.z);
  int hits = 0;
  for (int k = 0; k < samples; ++k) {
    const Vec3 p(ux(rng), uy(rng), uz(rng));
    hits += box.distance(p) >= 0.0 && test::in_lattice(bridged, p);
  }
  const Vec3 e = hi - lo;
  const double box_volume = e.x * e.y * e.z, frac = double(hits) / samples;
  return {frac * box_volume, std::sqrt(frac * (1 - frac) / samples) * box_volume};
}

// The bridge trim of `f` into `body`, with the lines it logged; checked to be one valid solid.
struct BridgedPart {
  TrimResult result;
  std::vector<std::string> messages;
  bool logged(const std::string& text) const {
    return std::any_of(messages.begin(), messages.end(),
                       [&](const std::string& m) { return m.find(text) != std::string::npos; });
  }
};
BridgedPart bridge_trim(const FlatLattice& f, const TopoDS_Shape& body) {
  BridgedPart out;
  TrimOptions o;
  o.policy = TrimPolicy::Bridge;
  o.report = [&](const std::string& m) { out.messages.push_back(m); };
  out.result = trim_lattice(f, body, o);
  EXPECT_TRUE(is_valid(out.result.part)) << validity_report(out.result.part);
  EXPECT_EQ(solid_count(out.result.part), 1);
  return out;
}

// Hub A keeps a beam to hub K and loses one to X outside the box; its nearest wall point (1, 0, 0) lies beyond
// K, so that bridge would run through K's ball. It is rerouted: the rings at 10 and 20 degrees about +x still pass
// too close to K (0.6 sin 20 < 0.15 + 0.1), the first direction of the 30-degree ring is clear and shorter than
// the lost beam's route (3, down to z = -3). The bridge is checked by brute force against every kept element,
// ends on the wall, and the part is one valid solid with A and K whole, of the Monte Carlo volume.
TEST(TrimBridge, ABridgeThroughAnotherHubIsRerouted) {
  const FlatLattice f = make_flat_lattice({{{0, 0, 0}, 0.2}, {{0.6, 0, 0}, 0.15}, {{0, 0, -3.5}, 0.2}},
                                          {{0, 1, 0.08, 0.08}, {0, 2, 0.1, 0.1}});
  const TestBox box{{-1.2, -2, -3}, {1, 2, 3}};
  const BridgePlan plan = plan_bridges(f, box.shape(), 0.0);
  EXPECT_EQ(plan.kept, (std::vector<std::int64_t>{0, 1}));
  EXPECT_TRUE(plan.blocked.empty());
  ASSERT_EQ(plan.bridges.size(), 1u);
  const Bridge& b = plan.bridges[0];
  EXPECT_EQ(b.hub, 0);
  EXPECT_TRUE(b.rerouted);
  EXPECT_FALSE(b.ambiguous);
  EXPECT_EQ(b.radius, 0.1);
  // Its route: the first of the 30-degree ring, (cos 30, 0, sin 30), to the wall x = 1.
  EXPECT_NEAR(glm::length(b.wall), 1.0 / std::cos(kPi / 6), 1e-9);
  EXPECT_NEAR(b.wall.z / b.wall.x, std::tan(kPi / 6), 1e-9);
  EXPECT_NEAR(box.distance(b.wall), 0.0, 1e-6) << "the wall point is on the wall";
  // Its far node is past the wall along the same line, its ball clear of the box.
  EXPECT_NEAR(glm::length(glm::cross(b.wall, b.end)), 0.0, 1e-9);
  EXPECT_LE(box.distance(b.end), -b.radius);
  // Clear of every kept element but its own hub's, by brute force; the nearest route was not.
  EXPECT_GT(brute_force_clearance(f, plan.kept, b), 0.0);
  Bridge nearest = b;
  nearest.end = Vec3(1.0 + 1.5 * b.radius, 0, 0);
  EXPECT_LT(brute_force_clearance(f, plan.kept, nearest), 0.0);

  const BridgedPart bridged = bridge_trim(f, box.shape());
  const TrimResult& r = bridged.result;
  EXPECT_EQ(r.stats.kept_hubs, 2);
  EXPECT_EQ(r.stats.lost_neighbour_hubs, 1);
  EXPECT_EQ(r.stats.bridges, 1);
  EXPECT_EQ(r.stats.rerouted_bridges, 1);
  EXPECT_EQ(r.stats.blocked_bridges, 0);
  EXPECT_TRUE(bridged.logged("bridge from hub 0 rerouted"));
  for (std::int64_t i : plan.kept) EXPECT_TRUE(part_contains(r.part, f.balls[i].center)) << "hub " << i;
  const auto [estimate, sigma] = box_monte_carlo(plan.lattice, box, {-0.3, -0.3, -0.3}, {1.0, 0.3, 1.0}, 200000);
  const double volume = shape_volume(r.part);
  EXPECT_NEAR(volume, estimate, 4 * sigma);
  std::printf("[ bridge   ] rerouted: wall point (%.4f, %.4f, %.4f), volume %.5f, Monte Carlo %.5f +- %.5f\n",
              b.wall.x, b.wall.y, b.wall.z, volume, estimate, sigma);
}

// Hub A in a cage of kept hubs: the 26 points of the cube of side 1 about it (balls 0.15), every two adjacent
// ones joined (beams 0.08), the six on the axes joined to A. A loses a beam of radius 0.15 to X below the box
// (whose nearest wall, z = -1.5, lies 1.5 from A), so its bridge (radius 0.15) fits through no gap of the cage:
// checked here by sampling 2,000 directions.
// Every route is blocked: the bridge is not made, counted and named, and the part is the cage and A, whole.
TEST(TrimBridge, AHubBoxedInByKeptHubsStaysBlocked) {
  std::vector<Ball> balls{{{0, 0, 0}, 0.2}};
  std::vector<FlatBeam> beams;
  std::vector<Vec3> grid{{0, 0, 0}};
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k)
        if (i || j || k) {
          grid.emplace_back(i, j, k);
          balls.push_back({Vec3(i, j, k) * 0.5, 0.15});
          if (std::abs(i) + std::abs(j) + std::abs(k) == 1)
            beams.push_back({0, std::int64_t(balls.size() - 1), 0.06, 0.06});
        }
  for (std::size_t a = 1; a < grid.size(); ++a)
    for (std::size_t c = a + 1; c < grid.size(); ++c) {
      const Vec3 d = glm::abs(grid[a] - grid[c]);
      if (d.x + d.y + d.z == 1.0) beams.push_back({std::int64_t(a), std::int64_t(c), 0.08, 0.08});
    }
  balls.push_back({{0.9, 0.9, -1.8}, 0.2});
  beams.push_back({0, std::int64_t(balls.size() - 1), 0.15, 0.15});
  const FlatLattice f = make_flat_lattice(balls, beams);
  const TestBox box{{-2, -2, -1.5}, {2, 2, 3}};
  const BridgePlan plan = plan_bridges(f, box.shape(), 0.0);
  EXPECT_EQ(plan.kept.size(), 27u);
  EXPECT_EQ(plan.lost_neighbour_hubs, 1);
  EXPECT_TRUE(plan.bridges.empty());
  EXPECT_EQ(plan.blocked, (std::vector<std::int64_t>{0}));
  // No route from A to the wall is clear, whatever the direction: every bridge through the cage meets it.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  for (int k = 0; k < 2000; ++k) {
    // The bridge's first unit of length (the cage's farthest point lies 0.87 + 0.15 from A, the wall farther),
    // sampled with the cage's balls and beams: a sampled overlap is a true one.
    const Vec3 u = glm::normalize(Vec3(normal(rng), normal(rng), normal(rng)));
    double least = std::numeric_limits<double>::infinity();
    for (int s = 0; s <= 60; ++s) {
      const Vec3 p = u * (s / 60.0);
      for (std::int64_t i = 1; i < f.ball_count() - 1; ++i)
        least = std::min(least, glm::length(f.balls[i].center - p) - f.balls[i].radius - 0.15);
      for (const FlatBeam& b : beams)
        if (b.a != 0)
          for (int t = 0; t <= 30; ++t) {
            const Vec3 q = f.balls[b.a].center + (f.balls[b.b].center - f.balls[b.a].center) * (t / 30.0);
            least = std::min(least, glm::length(q - p) - b.ra - 0.15);
          }
    }
    ASSERT_LT(least, 0.0) << "a free direction: " << u.x << " " << u.y << " " << u.z;
  }

  const BridgedPart bridged = bridge_trim(f, box.shape());
  const TrimResult& r = bridged.result;
  EXPECT_EQ(r.stats.kept_hubs, 27);
  EXPECT_EQ(r.stats.bridges, 0);
  EXPECT_EQ(r.stats.rerouted_bridges, 0);
  EXPECT_EQ(r.stats.blocked_bridges, 1);
  EXPECT_TRUE(bridged.logged("no bridge from hub 0"));
  const auto [estimate, sigma] = box_monte_carlo(plan.lattice, box, Vec3(-0.7), Vec3(0.7), 100000);
  const double volume = shape_volume(r.part);
  EXPECT_NEAR(volume, estimate, 4 * sigma);
  std::printf("[ bridge   ] boxed in: volume %.5f, Monte Carlo %.5f +- %.5f\n", volume, estimate, sigma);
}

// A hub on a cylinder's axis has a circle of nearest points: one is taken, the bridge counted as ambiguous, and
// the bridge still ends in the wall.
TEST(TrimBridge, AHubOnTheMedialAxisTakesOneNearestPoint) {
  const FlatLattice f = make_flat_lattice({{{0, 0, 0}, 0.3}, {{0, 0, -4}, 0.3}}, {{0, 1, 0.15, 0.15}});
  const TopoDS_Shape body = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -3), gp_Dir(0, 0, 1)), 1.0, 6.0).Shape();
  const BridgePlan plan = plan_bridges(f, body, 0.0);
  ASSERT_EQ(plan.bridges.size(), 1u);
  EXPECT_TRUE(plan.bridges[0].ambiguous);
  EXPECT_NEAR(std::hypot(plan.bridges[0].wall.x, plan.bridges[0].wall.y), 1.0, 1e-7);
  EXPECT_NEAR(plan.bridges[0].wall.z, 0.0, 1e-7);
  const TrimResult r = bridge_trim(f, body).result;
  EXPECT_EQ(r.stats.ambiguous_bridges, 1);
  // The ball and the bridge, cut flush at the wall: between the ball plus the bridge's cylinder to the wall
  // (overlap counted twice) and the ball alone plus the part of that cylinder outside the ball.
  const double ball = 4.0 / 3.0 * kPi * 0.027, rod = kPi * 0.15 * 0.15;
  const double v = shape_volume(r.part);
  EXPECT_GT(v, ball + rod * (1.0 - 0.3) - 1e-3);
  EXPECT_LT(v, ball + rod * 1.0);
}

// The bridge trim reports growing fractions up to 1, through the plan (classification, nearest points) and the
// clip of the bridged lattice; cancelled early (in the plan) or late (in the clip), it throws Cancelled, and a full
// run afterwards gives the same part.
TEST(TrimBridge, ReportsProgressAndCancels) {
  const FlatLattice f = grid_lattice(5);
  const TopoDS_Shape body = cylinder().shape;
  TrimOptions o;
  o.policy = TrimPolicy::Bridge;
  std::vector<double> seen;
  Progress full([&](double x) {
    seen.push_back(x);
    return true;
  });
  full.set_report_interval(std::chrono::milliseconds(0));
  const TrimResult reference = trim_lattice(f, body, o, full);
  ASSERT_GE(seen.size(), 10u);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
  EXPECT_TRUE(std::any_of(seen.begin(), seen.end(), [](double x) { return x > 0.0 && x < 0.1; }))
      << "nothing reported during the plan";
  for (double stop : {0.02, 0.5}) {
    std::vector<double> stopped;
    Progress p([&](double x) {
      stopped.push_back(x);
      return x < stop;
    });
    p.set_report_interval(std::chrono::milliseconds(0));
    EXPECT_THROW(trim_lattice(f, body, o, p), Cancelled) << stop;
    ASSERT_FALSE(stopped.empty());
    EXPECT_GE(stopped.back(), stop);
    EXPECT_LT(stopped.back(), 1.0);
  }
  const TrimResult again = trim_lattice(f, body, o);
  EXPECT_NEAR(shape_volume(again.part) / shape_volume(reference.part), 1.0, 1e-12);
  EXPECT_EQ(again.stats.bridges, reference.stats.bridges);
}

TEST(TrimBridge, BadInputNamesThePolicy) {
  try {
    trim_policy_from_string("bridges");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("'bridge'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("policy"), std::string::npos) << e.what();
  }
  // Every hub crosses the wall: nothing to keep, nothing to bridge.
  const FlatLattice f = grid_lattice(3);
  const TopoDS_Shape thin = BRepPrimAPI_MakeBox(gp_Pnt(-0.5, -0.5, 0.9), gp_Pnt(2.5, 2.5, 1.1)).Shape();
  TrimOptions o;
  o.policy = TrimPolicy::Bridge;
  try {
    trim_lattice(f, thin, o);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("policy"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'bridge'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace steady
