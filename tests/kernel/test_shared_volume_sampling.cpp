// The volume overlapping hubs share, integrated along lines where their pieces meet (the check of the properties'
// cluster Fuse), against the closed form of two balls' lens and against plain point sampling of the same integrand
// over the hubs' whole box (the slow, obviously right twin).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "lattice_test_shapes.hpp"
#include "properties/shared_volume_sampling.hpp"
#include "steady/core/constants.hpp"
#include "steady/lattice/hub.hpp"
#include "steady/query/hub_overlaps.hpp"

namespace steady {
namespace {

Hub lone_ball(const Vec3& center, double radius) {
  Hub h;
  h.ball = Ball{center, radius};
  return h;
}

// Plain sampling: uniform points of the box around all hubs, each counting (hubs holding it - 1) where positive.
std::pair<double, double> point_sampled_shared_volume(const std::vector<Hub>& hubs, int samples, std::uint64_t seed,
                                                      HubReading reading = HubReading::Whole) {
  const auto [lo, hi] = hubs_bounds(hubs);
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double sum = 0.0, squares = 0.0;
  for (int i = 0; i < samples; ++i) {
    const double x = unit(random), y = unit(random), z = unit(random);
    const Vec3 p = lo + (hi - lo) * Vec3(x, y, z);
    int holding = 0;
    for (const Hub& h : hubs) holding += inside_hub(h, p, reading) ? 1 : 0;
    const double w = std::max(0, holding - 1);
    sum += w;
    squares += w * w;
  }
  const double box = (hi.x - lo.x) * (hi.y - lo.y) * (hi.z - lo.z);
  const double mean = sum / samples;
  return {box * mean, box * std::sqrt((squares / samples - mean * mean) / samples)};
}

std::vector<Hub> all_hubs(const Lattice& lat) {
  std::vector<Hub> hubs;
  lat.for_each_ball([&](std::int64_t, const NodeId& n, const Ball&) { hubs.push_back(hub(lat, n)); });
  return hubs;
}

TEST(SharedVolumeSampling, TwoBallsShareTheirLens) {
  // Balls of radius R at distance d share pi (4R + d)(2R - d)^2 / 12; a third ball apart shares nothing.
  const double R = 0.4, d = 0.5;
  const double lens = kPi * (4 * R + d) * (2 * R - d) * (2 * R - d) / 12.0;
  const std::vector<Hub> hubs{lone_ball(Vec3(0.0), R), lone_ball(Vec3(0.3, 0.4, 0.0), R),
                              lone_ball(Vec3(3.0, 0.0, 0.0), R)};
  const auto [shared, sigma] = sampled_shared_volume(hubs, 10000, 7);
  std::printf("[ report ] lens %.9f, lines %.9f +- %.1e\n", lens, shared, sigma);
  EXPECT_NEAR(shared, lens, 5 * sigma + 1e-12);
  EXPECT_LT(sigma, 2e-3 * lens);  // the chords' square-root edge at the lens rim limits the grid
  EXPECT_GT(sigma, 0.0);
  const auto [apart, none] = sampled_shared_volume({hubs[0], hubs[2]}, 10000, 7);
  EXPECT_EQ(apart, 0.0);
  EXPECT_EQ(none, 0.0);
}

TEST(SharedVolumeSampling, ThreeBallsCountWhatTheyShareTwice) {
  // Three equal balls around one point: the integrand is 2 where all three hold a point, and the lines give the
  // sum of the pair lenses less the triple part once (sum of volumes less the union), as the points do.
  const double R = 0.5;
  const std::vector<Hub> hubs{lone_ball(Vec3(0.0), R), lone_ball(Vec3(0.6, 0.0, 0.0), R),
                              lone_ball(Vec3(0.3, 0.5, 0.0), R)};
  const auto [lines, sigma] = sampled_shared_volume(hubs, 30000, 11);
  const auto [points, point_sigma] = point_sampled_shared_volume(hubs, 2000000, 5);
  std::printf("[ report ] three balls: lines %.7f +- %.1e, points %.7f +- %.1e\n", lines, sigma, points, point_sigma);
  EXPECT_NEAR(lines, points, 5 * std::hypot(sigma, point_sigma));
  EXPECT_LT(sigma, 0.5 * point_sigma);  // 30,000 lines against 2 million points
}

TEST(SharedVolumeSampling, CrowdedLatticesAgreeWithPointSampling) {
  // Nodes near each other with thicker beams than HubUnion's: balls meet beams and beams meet beams of other hubs.
  std::mt19937_64 rng(2027);
  int compared = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const Lattice lat(test::two_close_nodes(rng, 0.08, 0.08, 2));
    if (check_hub_overlaps(lat).overlap_count == 0) continue;
    const std::vector<Hub> hubs = all_hubs(lat);
    const auto [lines, sigma] = sampled_shared_volume(hubs, 100000, 3 + trial);
    const auto [points, point_sigma] = point_sampled_shared_volume(hubs, 2000000, 17 + trial);
    std::printf("[ report ] trial %d: lines %.7f +- %.1e, points %.7f +- %.1e\n", trial, lines, sigma, points,
                point_sigma);
    EXPECT_GT(lines, 0.0) << trial;
    EXPECT_NEAR(lines, points, 5 * std::hypot(sigma, point_sigma)) << trial;
    EXPECT_LT(sigma, 0.3 * point_sigma) << trial;  // 100,000 lines against 2 million points
    ++compared;
  }
  EXPECT_GE(compared, 3);
}

TEST(SharedVolumeSampling, AHubClosedAtACutInsideItsBallLosesWhatLiesBeyondTheCut) {
  // Unit balls at x = 0 and x = 1.5 share a lens over 0.5 <= x <= 1. The first has a straight stump of radius 0.5
  // along x cut at x = 0.5, inside its ball: read whole the stump changes nothing; closed at its cut, the stump's
  // cylinder beyond x = 0.5 is not the hub's, and the lens keeps only what lies outside radius 0.5:
  // 2 pi (integral from 0.75 to sqrt(0.75) of 0.75 - x^2).
  Hub a = lone_ball(Vec3(0.0), 1.0);
  Stump s;
  s.cone = beam_cone(Ball{Vec3(0.0), 0.5}, Ball{Vec3(3.0, 0.0, 0.0), 0.5});
  s.cut_position = 0.5;
  s.cut = Circle{Vec3(0.5, 0.0, 0.0), Vec3(1.0, 0.0, 0.0), 0.5};
  a.stumps.push_back(s);
  const std::vector<Hub> hubs{a, lone_ball(Vec3(1.5, 0.0, 0.0), 1.0)};
  const double lens = kPi * (4.0 + 1.5) * 0.5 * 0.5 / 12.0;
  const double root = std::sqrt(0.75);
  auto antiderivative = [](double x) { return 0.75 * x - x * x * x / 3.0; };
  const double outside = 2.0 * kPi * (antiderivative(root) - antiderivative(0.75));
  const auto [whole, whole_sigma] = sampled_shared_volume(hubs, 40000, 5);
  const auto [closed, closed_sigma] = sampled_shared_volume(hubs, 40000, 5, HubReading::ClosedAtCuts);
  std::printf("[ report ] whole %.7f +- %.1e (lens %.7f), closed %.7f +- %.1e (%.7f)\n", whole, whole_sigma, lens,
              closed, closed_sigma, outside);
  EXPECT_NEAR(whole, lens, 5 * whole_sigma + 1e-12);
  EXPECT_NEAR(closed, outside, 5 * closed_sigma + 1e-12);
  EXPECT_LT(closed_sigma, 5e-3 * outside);
  EXPECT_FALSE(inside_hub(a, Vec3(0.9, 0.1, 0.0), HubReading::ClosedAtCuts));
  EXPECT_TRUE(inside_hub(a, Vec3(0.9, 0.1, 0.0)));
  EXPECT_TRUE(inside_hub(a, Vec3(0.4, 0.1, 0.0), HubReading::ClosedAtCuts));
  EXPECT_TRUE(inside_hub(a, Vec3(0.7, 0.0, 0.6), HubReading::ClosedAtCuts));
}

TEST(SharedVolumeSampling, HubsClosedAtCutsInsideTheirBallsAgreeWithPointSampling) {
  // Crowded lattices as above (beams up to 0.14, under the smaller node's 0.15) with every cut moved to a random
  // place between the ball's center and the mid-plane (inside the ball for many): B-rep cores closed by tight
  // collars (brep/hub_group.cpp), against points read the same way.
  std::mt19937_64 rng(2029);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int compared = 0, changed = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const Lattice lat(test::two_close_nodes(rng, 0.06, 0.08, 2));
    if (check_hub_overlaps(lat).overlap_count == 0) continue;
    std::vector<Hub> hubs = all_hubs(lat);
    for (Hub& h : hubs)
      for (Stump& s : h.stumps) move_cut(s, (0.2 + 0.8 * unit(rng)) * s.cut_position);
    const auto [lines, sigma] = sampled_shared_volume(hubs, 100000, 3 + trial, HubReading::ClosedAtCuts);
    const auto [points, point_sigma] =
        point_sampled_shared_volume(hubs, 2000000, 17 + trial, HubReading::ClosedAtCuts);
    const auto [whole, whole_sigma] = sampled_shared_volume(hubs, 100000, 3 + trial);
    std::printf("[ report ] trial %d: lines %.7f +- %.1e, points %.7f +- %.1e; read whole %.7f\n", trial, lines,
                sigma, points, point_sigma, whole);
    EXPECT_NEAR(lines, points, 5 * std::hypot(sigma, point_sigma)) << trial;
    EXPECT_LT(sigma, 0.3 * point_sigma) << trial;
    if (std::abs(whole - lines) > 5 * std::hypot(sigma, whole_sigma)) ++changed;
    ++compared;
  }
  EXPECT_GE(compared, 3);
  EXPECT_GE(changed, 1) << "no trial put a cut where the reading matters";
}

}  // namespace
}  // namespace steady
