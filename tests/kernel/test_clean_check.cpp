// The clean check: GJK against dense sampling, the grid broad phase against all pairs, and the whole check
// against its brute-force twin on random lattices, plus hand-made lattices with known offenders.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <tuple>

#include "steady/lattice/beam_frustum.hpp"
#include "steady/lattice/broad_phase.hpp"
#include "steady/query/clean_check.hpp"
#include "steady/lattice/convex_distance.hpp"
#include "steady/core/errors.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "test_lattices.hpp"
#include "test_support.hpp"
#include "brick_definition.hpp"

namespace steady {
namespace {

using test::random_unit;
using test::random_vec;

// Points densely covering a frustum's surface (both disks and the lateral surface).
std::vector<Vec3> frustum_samples(const Circle& a, const Circle& b, int n) {
  std::vector<Vec3> out;
  Vec3 u = glm::cross(a.normal, Vec3(1, 0, 0));
  if (glm::length(u) < 0.1) u = glm::cross(a.normal, Vec3(0, 1, 0));
  u = glm::normalize(u);
  const Vec3 v = glm::cross(a.normal, u);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    const Vec3 dir = std::cos(t) * u + std::sin(t) * v;
    for (int j = 0; j <= n; ++j) {
      const double s = double(j) / n;
      out.push_back(a.center + s * a.radius * dir);
      out.push_back(b.center + s * b.radius * dir);
      out.push_back((1 - s) * (a.center + a.radius * dir) + s * (b.center + b.radius * dir));
    }
  }
  return out;
}

TEST(ConvexDistance, FrustumPairsMatchDenseSampling) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int separated = 0, intersecting = 0;
  for (int trial = 0; trial < 60; ++trial) {
    Circle f[2][2];
    for (auto& fr : f) {
      const Vec3 c = random_vec(rng, 0.8), n = random_unit(rng);
      const double len = 0.5 + u01(rng);
      fr[0] = {c, n, 0.1 + 0.3 * u01(rng)};
      fr[1] = {c + len * n, n, 0.1 + 0.3 * u01(rng)};
    }
    const DistanceBounds d = convex_distance([&](const Vec3& v) { return disk_hull_support(f[0][0], f[0][1], v); },
                                             [&](const Vec3& v) { return disk_hull_support(f[1][0], f[1][1], v); },
                                             1e300, -1.0, 1e-12, 1000);
    const auto p = frustum_samples(f[0][0], f[0][1], 30), q = frustum_samples(f[1][0], f[1][1], 30);
    double sampled = 1e300;
    for (const Vec3& x : p)
      for (const Vec3& y : q) sampled = std::min(sampled, glm::length(x - y));
    // GJK's lower bound can never exceed a true distance between surface points; when the bodies are apart,
    // the sampled minimum approaches the true distance to within the sampling step.
    EXPECT_LE(d.lower, sampled + 1e-12);
    if (d.intersecting || d.upper < 1e-9) {
      ++intersecting;
    } else {
      ++separated;
      EXPECT_NEAR(d.upper, d.lower, 1e-7 * d.upper + 1e-12);
      EXPECT_LE(d.upper, sampled + 1e-9);
      EXPECT_NEAR(d.upper, sampled, 0.05);
    }
  }
  EXPECT_GT(separated, 10);
  EXPECT_GT(intersecting, 5);
}

TEST(ConvexDistance, SphereAgainstPointIsExact) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 c = random_vec(rng, 2.0), p = random_vec(rng, 2.0);
    const double r = 0.3;
    const DistanceBounds d = convex_distance([&](const Vec3& v) { return c + r * v / glm::length(v); },
                                             [&](const Vec3&) { return p; }, 1e300, -1.0);
    const double exact = std::max(0.0, glm::length(c - p) - r);
    if (exact > 1e-9) EXPECT_NEAR(d.upper, exact, 1e-9);
    else EXPECT_LT(d.lower, 1e-9);
  }
}

TEST(BroadPhase, GridFindsExactlyTheOverlappingPairs) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Box> boxes;
    const int n = 200 + 50 * trial;
    for (int i = 0; i < n; ++i) {
      const Vec3 c = random_vec(rng, 10.0);
      // Mostly small boxes, a few huge ones and some flat ones.
      const double s = (i % 97 == 0) ? 8.0 : 0.2 + 0.8 * u01(rng);
      // One draw per statement, in GCC's order (last argument first): the sample is the same whatever compiles it.
      const double ez = s * u01(rng), ey = s * u01(rng), ex = s * u01(rng);
      Vec3 e(ex, ey, ez);
      if (i % 13 == 0) e.z = 0.0;
      boxes.push_back({c - e, c + e});
    }
    auto fast = overlapping_box_pairs(boxes), slow = overlapping_box_pairs_brute_force(boxes);
    std::sort(fast.begin(), fast.end());
    std::sort(slow.begin(), slow.end());
    EXPECT_EQ(fast, slow);
    EXPECT_EQ(std::adjacent_find(fast.begin(), fast.end()), fast.end()) << "a pair was reported twice";
  }
}

std::vector<std::tuple<int, std::int64_t, std::int64_t, std::int64_t, std::int64_t>> issue_keys(const CleanReport& r) {
  std::vector<std::tuple<int, std::int64_t, std::int64_t, std::int64_t, std::int64_t>> out;
  for (const CleanIssue& i : r.issues) out.emplace_back(int(i.kind), i.ball, i.other_ball, i.beam, i.other_beam);
  return out;
}

TEST(CleanCheck, StrutLatticesWithThinBeamsAreClean) {
  std::mt19937_64 rng(5);
  for (int kind = 0; kind < 4; ++kind) {
    const Lattice lat = test::strut_lattice(rng, test::StepKind(kind), {4, 3, 3}, 0.25);
    const CleanReport r = check_clean(lat);
    EXPECT_TRUE(r.clean()) << "kind " << kind << ": " << (r.issues.empty() ? "" : r.issues[0].describe());
    EXPECT_GT(r.candidate_pairs, 0);
  }
}

// A lattice with random beam patterns (offsets up to one group in each direction, random end radii): crossing
// diagonals, beams grazing foreign balls and crowded hubs all occur.
Lattice messy_lattice(std::mt19937_64& rng, double node_radius) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::uniform_int_distribution<int> offset(-1, 1);
  test::BrickDefinition d;
  d.nodes = {{{0, 0, 0}, node_radius}, {{0.4, 0.5, 0.45}, node_radius * (0.5 + u01(rng))}};
  std::set<std::tuple<int, int, int, int, int>> used;
  while (d.beams.size() < 6) {
    BeamPattern b{int(u01(rng) * 2), offset(rng), offset(rng), offset(rng), int(u01(rng) * 2)};
    if (b.di == 0 && b.dj == 0 && b.dk == 0 && b.from == b.to) continue;
    if (used.count({b.from, b.di, b.dj, b.dk, b.to})) continue;
    used.insert({b.from, b.di, b.dj, b.dk, b.to});
    used.insert({b.to, -b.di, -b.dj, -b.dk, b.from});
    const double rmax = std::min(d.nodes[b.from].radius, d.nodes[b.to].radius);
    b.from_radius = rmax * (0.2 + 0.5 * u01(rng));
    b.to_radius = rmax * (0.2 + 0.5 * u01(rng));
    d.beams.push_back(b);
  }
  d.counts = {3, 3, 2};
  d.u = {Similarity::translation({1, 0, 0})};
  d.v = {Similarity::swirl(0.05, {1, 0, 0}, {0, -20, 0}, 1.0) * Similarity::translation({0, 1, 0})};
  d.w = {Similarity::translation({0.1, 0, 1})};
  return Lattice(std::move(d));
}

TEST(CleanCheck, MatchesBruteForceOnRandomLattices) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int clean = 0, dirty = 0;
  std::set<CleanIssueKind> kinds;
  for (int trial = 0; trial < 60; ++trial) {
    // Node radii from thin to fat: fat nodes make balls, caps and beams collide.
    const double radius = 0.1 + 0.4 * u01(rng);
    Lattice lat = test::strut_lattice(rng, test::StepKind(trial % 4), {3, 3, 2}, radius);
    if (trial % 3 == 1) lat = test::bcc_lattice(rng, {3, 2, 2}, radius, 0.1 + 0.4 * u01(rng));
    if (trial % 3 == 2) lat = messy_lattice(rng, 0.05 + 0.2 * u01(rng));
    const FlatLattice flat = flatten(lat);
    const CleanReport fast = check_clean(flat), slow = check_clean_brute_force(flat);
    EXPECT_EQ(fast.issue_count, slow.issue_count) << "trial " << trial;
    EXPECT_EQ(issue_keys(fast), issue_keys(slow)) << "trial " << trial;
    EXPECT_LE(fast.candidate_pairs, slow.candidate_pairs);
    (fast.clean() ? clean : dirty)++;
    for (const CleanIssue& i : fast.issues) kinds.insert(i.kind);
  }
  EXPECT_GT(clean, 3);
  EXPECT_GT(dirty, 3);
  EXPECT_EQ(kinds.size(), 4u) << "every kind of issue should occur in the sample";
}

// Hand-made lattices whose offenders are known.
TEST(CleanCheck, ReportsKnownOffenders) {
  // Two balls at (0,0,0) and (4,0,0), one beam between them; a third ball at (2, 0.5, 0) touches the beam.
  {
    FlatLattice f = make_flat_lattice({{{0, 0, 0}, 1.0}, {{4, 0, 0}, 1.0}, {{2, 0.5, 0}, 0.4}}, {{0, 1, 0.3, 0.3}});
    const CleanReport r = check_clean(f);
    ASSERT_EQ(r.issue_count, 1);
    EXPECT_EQ(r.issues[0].kind, CleanIssueKind::BallBeam);
    EXPECT_EQ(r.issues[0].ball, 2);
    EXPECT_EQ(r.issues[0].beam, 0);
  }
  // Two beams from one ball at 30 degrees with radii 0.5 on a unit ball: caps of ~30 degrees each overlap.
  {
    const double a = M_PI / 6;
    FlatLattice f = make_flat_lattice({{{0, 0, 0}, 1.0}, {{5, 0, 0}, 1.0}, {{5 * std::cos(a), 5 * std::sin(a), 0}, 1.0}},
                                      {{0, 1, 0.5, 0.5}, {0, 2, 0.5, 0.5}});
    const CleanReport r = check_clean(f);
    ASSERT_GE(r.issue_count, 1);
    EXPECT_EQ(r.issues[0].kind, CleanIssueKind::CircleOverlap);
    EXPECT_EQ(r.issues[0].ball, 0);
  }
  // The two diagonals of a square cross at its centre.
  {
    FlatLattice f = make_flat_lattice({{{0, 0, 0}, 0.2}, {{3, 0, 0}, 0.2}, {{3, 3, 0}, 0.2}, {{0, 3, 0}, 0.2}},
                                      {{0, 2, 0.1, 0.1}, {1, 3, 0.1, 0.1}});
    const CleanReport r = check_clean(f);
    ASSERT_EQ(r.issue_count, 1);
    EXPECT_EQ(r.issues[0].kind, CleanIssueKind::BeamBeam);
    EXPECT_EQ(r.issues[0].beam, 0);
    EXPECT_EQ(r.issues[0].other_beam, 1);
  }
  // Lift one diagonal by more than the beam radii: clean.
  {
    FlatLattice f = make_flat_lattice({{{0, 0, 0}, 0.2}, {{3, 0, 0}, 0.2}, {{3, 3, 0}, 0.2}, {{0, 3, 0.6}, 0.2}},
                                      {{0, 2, 0.1, 0.1}, {1, 3, 0.1, 0.1}});
    EXPECT_TRUE(check_clean(f).clean());
  }
  // A small ball nested in a big one through a degenerate beam is absorbed; a partly overlapping one is not.
  {
    FlatLattice f = make_flat_lattice({{{0, 0, 0}, 1.0}, {{0.3, 0, 0}, 0.5}, {{5, 0, 0}, 1.0}},
                                      {{0, 1, 0.9, 0.4}, {0, 2, 0.3, 0.3}});
    const CleanReport r = check_clean(f);
    EXPECT_TRUE(r.clean()) << (r.issues.empty() ? "" : r.issues[0].describe());
    EXPECT_EQ(r.absorbed_balls, std::vector<std::int64_t>{1});
    EXPECT_EQ(r.degenerate_beams, std::vector<std::int64_t>{0});
    FlatLattice g = make_flat_lattice({{{0, 0, 0}, 1.0}, {{0.8, 0, 0}, 0.5}}, {{0, 1, 0.9, 0.4}});
    const CleanReport s = check_clean(g);
    ASSERT_EQ(s.issue_count, 1);
    EXPECT_EQ(s.issues[0].kind, CleanIssueKind::BallBall);
  }
}

TEST(CleanCheck, HullModelHubsAreNotClean) {
  // Without explicit radii the beams are tangent to their nodes: on every ball with two beams the tangent
  // circles are near-great circles that cross.
  test::BrickDefinition d;
  d.nodes = {{{0, 0, 0}, 0.2}};
  d.beams = {{0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}};
  d.counts = {3, 3, 1};
  d.u = {Similarity::translation({1, 0, 0})};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::translation({0, 0, 1})};
  const CleanReport r = check_clean(Lattice(d));
  EXPECT_FALSE(r.clean());
  for (const CleanIssue& i : r.issues) EXPECT_EQ(i.kind, CleanIssueKind::CircleOverlap);
}

TEST(CleanCheck, BadInputNamesTheElement) {
  EXPECT_THROW(make_flat_lattice({{{0, 0, 0}, -1.0}}, {}), InvalidInput);
  EXPECT_THROW(make_flat_lattice({{{0, 0, 0}, 1.0}, {{3, 0, 0}, 1.0}}, {{0, 2, 0.5, 0.5}}), InvalidInput);
  EXPECT_THROW(make_flat_lattice({{{0, 0, 0}, 1.0}, {{3, 0, 0}, 1.0}}, {{0, 1, 1.5, 0.5}}), InvalidInput);
  try {
    make_flat_lattice({{{0, 0, 0}, 1.0}, {{3, 0, 0}, 1.0}}, {{0, 0, 0.5, 0.5}});
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("beams[0]"), std::string::npos);
  }
}

}  // namespace
}  // namespace steady
