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

// Hub A keeps a beam to hub K and loses one to X outside the box; its nearest wall point lies beyond K, so its
// bridge would run through K's ball: refused, reported, and the part is still A and K whole.
TEST(TrimBridge, ABridgeThroughAnotherHubIsRefusedAndReported) {
  const FlatLattice f = make_flat_lattice({{{0, 0, 0}, 0.2}, {{0.6, 0, 0}, 0.15}, {{0, 0, -3.5}, 0.2}},
                                          {{0, 1, 0.08, 0.08}, {0, 2, 0.1, 0.1}});
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(-1.2, -2, -3), gp_Pnt(1, 2, 3)).Shape();
  TrimOptions o;
  o.policy = TrimPolicy::Bridge;
  std::vector<std::string> messages;
  o.report = [&](const std::string& m) { messages.push_back(m); };
  const TrimResult r = trim_lattice(f, box, o);
  EXPECT_TRUE(is_valid(r.part)) << validity_report(r.part);
  EXPECT_EQ(solid_count(r.part), 1);
  EXPECT_EQ(r.stats.kept_hubs, 2);
  EXPECT_EQ(r.stats.lost_neighbour_hubs, 1);
  EXPECT_EQ(r.stats.blocked_bridges, 1);
  EXPECT_EQ(r.stats.bridges, 0);
  EXPECT_TRUE(std::any_of(messages.begin(), messages.end(),
                          [](const std::string& m) { return m.find("no bridge from hub 0") != std::string::npos; }));
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
  TrimOptions o;
  o.policy = TrimPolicy::Bridge;
  const TrimResult r = trim_lattice(f, body, o);
  EXPECT_TRUE(is_valid(r.part)) << validity_report(r.part);
  EXPECT_EQ(solid_count(r.part), 1);
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
