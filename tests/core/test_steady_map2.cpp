// Steady 2-maps and rectified steady slabs (constructive-lattice-geometry 2.6.4 to 2.6.6, 3.2 to 3.4): the five
// points and three frames interpolated, the field's order and steadiness, rectification exact where the map is a
// similarity and a true sphere through its four points elsewhere, the slab's groups placed by the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>

#include "steady/core/errors.hpp"
#include "steady/cots/steady_map2.hpp"

namespace {

using steady::Ball;
using steady::Counts;
using steady::Frame;
using steady::InvalidInput;
using steady::Lattice;
using steady::NodeId;
using steady::Similarity;
using steady::SteadyMap2;
using steady::TemplateNode;
using steady::Vec2;
using steady::Vec3;

Vec3 lift(const Vec2& p) { return Vec3(p.x, p.y, 0.0); }

// Five points of a warped square: corners jittered, the midpoint of ab pulled off the segment.
struct FivePoints {
  Vec2 a, b, c, d, e;
};
FivePoints random_points(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> j(-0.3, 0.3);
  FivePoints p{{j(rng), j(rng)}, {1 + j(rng), j(rng)}, {j(rng), 1 + j(rng)}, {1 + j(rng), 1 + j(rng)}, {}};
  p.e = 0.5 * (p.a + p.b) + Vec2(j(rng) * 0.3, j(rng) * 0.5);
  return p;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

TEST(SteadyMap2, FivePointsAreInterpolatedAndTheFieldIsVAfterU) {
  std::mt19937_64 rng(3);
  double worst = 0.0, worst_order = 0.0, worst_row = 0.0;
  for (int trial = 0; trial < 500; ++trial) {
    const FivePoints p = random_points(rng);
    const SteadyMap2 m = SteadyMap2::from_points(p.a, p.b, p.c, p.d, p.e);
    const std::pair<Vec2, Vec2> known[] = {{{0, 0}, p.a}, {{1, 0}, p.b}, {{0, 1}, p.c}, {{1, 1}, p.d}, {{0.5, 0}, p.e}};
    for (const auto& [uv, point] : known) worst = std::max(worst, glm::length(m.map(uv.x, uv.y) - lift(point)));
    // M(u, v) = V^v(U^u(O)), U applied first; along v every column is steady: M(u, v + h) = V^h(M(u, v)).
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double u = unit(rng), v = unit(rng), h = 0.25 * unit(rng);
    const Vec3 direct = m.v().power(v).apply_point(m.u().power(u).apply_point(m.origin()));
    worst_order = std::max(worst_order, glm::length(m.map(u, v) - direct));
    worst_row = std::max(worst_row, glm::length(m.map(u, v + h) - m.v().power(h).apply_point(m.map(u, v))));
    worst_row = std::max(worst_row, glm::length(m.map(u + h, 0) - m.u().power(h).apply_point(m.map(u, 0))));
    EXPECT_NEAR(m.map(u, v).z, 0.0, 1e-12);  // a planar map stays in its plane
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_order, 1e-12);
  EXPECT_LT(worst_row, 1e-12);
  std::printf("[ report ] 500 random five-point maps: points %.1e, V after U %.1e, steady rows %.1e\n", worst,
              worst_order, worst_row);
}

TEST(SteadyMap2, ASimilarityOfTheSquareGivesItselfAndExactRectification) {
  // Five points that are a similarity's images of the square's: U and V are that similarity's conjugated unit
  // translations, M is the similarity, and every domain ball is rectified to its exact image.
  const Similarity T = Similarity::swirl(0.7, {0, 0, 1}, {0.3, -0.2, 0}, 2.5) * Similarity::translation({1, 2, 0});
  auto image = [&](double u, double v) { const Vec3 q = T.apply_point({u, v, 0}); return Vec2(q.x, q.y); };
  const SteadyMap2 m = SteadyMap2::from_points(image(0, 0), image(1, 0), image(0, 1), image(1, 1), image(0.5, 0));
  EXPECT_NEAR(m.unit(), 2.5, 1e-12);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 100; ++k) {
    const Vec3 c(unit(rng), unit(rng), unit(rng) - 0.5);
    const double r = 0.05 + 0.2 * unit(rng);
    EXPECT_LT(glm::length(m.map(c.x, c.y) - T.apply_point({c.x, c.y, 0})), 1e-12);
    for (steady::Rectification method : {steady::Rectification::FourPoints, steady::Rectification::LeastSquares}) {
      const Ball b = m.rectify(c, r, "radius", method);
      EXPECT_LT(glm::length(b.center - T.apply_point(c)), 1e-12) << k;
      EXPECT_NEAR(b.radius, 2.5 * r, 1e-12) << k;
    }
  }
}

TEST(SteadyMap2, RectifiedBallsGoThroughTheirPointsAndTheFitApproachesTheWarp) {
  std::mt19937_64 rng(7);
  const FivePoints p = random_points(rng);
  const SteadyMap2 m = SteadyMap2::from_points(p.a, p.b, p.c, p.d, p.e);
  const double r = 0.1, s = r / std::sqrt(3.0);
  const Vec3 c(0.4, 0.6, 0.1);
  const Ball b = m.rectify(c, r);
  for (const Vec3& t : {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)})
    EXPECT_NEAR(glm::length(m.warp(c + s * t) - b.center), b.radius, 1e-12);
  // As the ball shrinks the map becomes its derivative there, a linear map that is not a similarity (U and V do not
  // commute, and w is scaled by the unit length alone): the sphere through four points of the ellipsoid is off its
  // center by a fixed fraction of its radius (the "different 4-point choice, different result" of 3.4), reached at
  // first order, and the warped center stays inside.
  double offset[3];
  const double radii[3] = {1e-2, 1e-3, 1e-4};
  for (int k = 0; k < 3; ++k) {
    const Ball t = m.rectify(c, radii[k]);
    offset[k] = glm::length(t.center - m.warp(c)) / t.radius;
    EXPECT_LT(offset[k], 1.0);
  }
  EXPECT_LT(std::abs(offset[2] - offset[1]), 0.2 * std::abs(offset[1] - offset[0]));
  // The least-squares sphere through 32 antipodal pairs is centred on the ellipsoid: its offset vanishes at first
  // order as the ball shrinks.
  for (int k = 0; k < 3; ++k) {
    const Ball t = m.rectify(c, radii[k], "radius", steady::Rectification::LeastSquares);
    offset[k] = glm::length(t.center - m.warp(c)) / t.radius;
  }
  EXPECT_LT(offset[1], 0.2 * offset[0]);
  EXPECT_LT(offset[2], 0.2 * offset[1]);
  EXPECT_LT(offset[2], 1e-3);
  std::printf("[ report ] rectified center off the warped one, in radii, at r = 1e-2, 1e-3, 1e-4: least squares %.1e "
              "%.1e %.1e\n", offset[0], offset[1], offset[2]);
}

TEST(SteadyMap2, ThreeFramesGiveA3DMapThroughTheirOrigins) {
  Frame a, b, c;
  b.origin = {2, 0, 0.5};
  b.x = {0.8, 0.6, 0};  // a turn about z, a dilation of 1.1
  b.y = {-0.6, 0.8, 0};
  b.x *= 1.1, b.y *= 1.1, b.z = Vec3(0, 0, 1.1);
  c.origin = {0, 1.5, 0.3};
  c.y = {0, 0.8, 0.6};  // a turn about x
  c.z = {0, -0.6, 0.8};
  const SteadyMap2 m = SteadyMap2::from_frames(a, b, c);
  EXPECT_LT(glm::length(m.map(0, 0) - a.origin), 1e-12);
  EXPECT_LT(glm::length(m.map(1, 0) - b.origin), 1e-12);
  EXPECT_LT(glm::length(m.map(0, 1) - c.origin), 1e-12);
  EXPECT_GT(std::abs(m.map(1, 1).z - 0.8), 1e-3);  // not a translation of the square: a 3D warp
  const Ball ball = m.rectify({0.5, 0.5, 0.0}, 0.1);
  EXPECT_TRUE(std::isfinite(ball.radius) && ball.radius > 0);
}

TEST(SteadyMap2, SlabGroupsArePlacedByTheFieldAndOnTheWarpWhereUAndVCommute) {
  std::mt19937_64 rng(11);
  const FivePoints p = random_points(rng);
  const SteadyMap2 m = SteadyMap2::from_points(p.a, p.b, p.c, p.d, p.e);
  const Counts counts{6, 5, 1};
  // A square grid: one node per tile, beams along u and v.
  steady::BeamPattern along_u, along_v;
  along_u.from = along_u.to = along_v.from = along_v.to = 0;
  along_u.di = 1, along_v.dj = 1;
  const std::vector<TemplateNode> nodes = {{{0.5, 0.5, 0.0}, 0.04}};
  const Lattice lat = steady::steady_slab_lattice(m, nodes, {along_u, along_v}, counts, 0.5);
  EXPECT_EQ(lat.ball_count(), 30);
  EXPECT_EQ(lat.beam_count(), 5 * 5 + 6 * 4);
  const Ball t = lat.ball({0, 0, 0, 0});
  const Ball expected_t = m.rectify({0.5 / 6, 0.5 / 5, 0.0}, 0.04);
  EXPECT_LT(glm::length(t.center - expected_t.center), 1e-12);
  for (std::int64_t i = 0; i < counts.u; ++i)
    for (std::int64_t j = 0; j < counts.v; ++j) {
      const Ball b = lat.ball({i, j, 0, 0});
      const Ball placed = m.field(double(i) / counts.u, double(j) / counts.v).apply(t);
      EXPECT_LT(glm::length(b.center - placed.center), 1e-12);
      EXPECT_NEAR(b.radius, placed.radius, 1e-12);
    }
  // Where U and V commute (the map a similarity of the square) the groups lie exactly where the warp puts their
  // tiles' nodes; otherwise they leave it by the steps' commutator, which is why the template alone is rectified.
  const Similarity T = Similarity::swirl(-0.4, {0, 0, 1}, {2, 1, 0}, 0.8);
  auto image = [&](double u, double v) { const Vec3 q = T.apply_point({u, v, 0}); return Vec2(q.x, q.y); };
  const SteadyMap2 similar =
      SteadyMap2::from_points(image(0, 0), image(1, 0), image(0, 1), image(1, 1), image(0.5, 0));
  const Lattice flat = steady::steady_slab_lattice(similar, nodes, {along_u, along_v}, counts, 0.5);
  for (std::int64_t i = 0; i < counts.u; ++i)
    for (std::int64_t j = 0; j < counts.v; ++j) {
      const Ball b = flat.ball({i, j, 0, 0});
      EXPECT_LT(glm::length(b.center - T.apply_point({(i + 0.5) / counts.u, (j + 0.5) / counts.v, 0.0})), 1e-12);
      EXPECT_NEAR(b.radius, 0.8 * 0.04, 1e-12);
    }
}

TEST(SteadyMap2, BadInputNamesThePointsFramesAndCounts) {
  const Vec2 a(0, 0), b(1, 0), c(0, 1), d(1, 1), e(0.5, 0.1);
  EXPECT_NE(message_of([&] { SteadyMap2::from_points(a, b, c, d, a); }).find("a, e"), std::string::npos);
  EXPECT_NE(message_of([&] { SteadyMap2::from_points(a, b, c, c, e); }).find("c, d"), std::string::npos);
  EXPECT_NE(message_of([&] { SteadyMap2::from_points(a, b, c, d, Vec2(NAN, 0)); }).find("e"), std::string::npos);
  Frame f, g, h;
  g.origin = {1, 0, 0};
  h.origin = {0, 1, 0};
  Frame skew = g;
  skew.y = {1, 1, 0};
  EXPECT_NE(message_of([&] { SteadyMap2::from_frames(f, skew, h); }).find("b"), std::string::npos);
  EXPECT_NE(message_of([&] { SteadyMap2::from_frames(f, f, h); }).find("b"), std::string::npos);
  const SteadyMap2 m = SteadyMap2::from_points(a, b, c, d, e);
  const std::vector<TemplateNode> nodes = {{{0.5, 0.5, 0.0}, 0.1}};
  EXPECT_NE(message_of([&] { steady::steady_slab_lattice(m, nodes, {}, Counts{2, 2, 2}); }).find("counts.w"),
            std::string::npos);
  EXPECT_NE(message_of([&] { steady::steady_slab_lattice(m, {{{0.5, 0.5, 0.0}, -1.0}}, {}, Counts{2, 2, 1}); })
                .find("nodes[0].radius"),
            std::string::npos);
  EXPECT_NE(message_of([&] { steady::steady_slab_lattice(m, {}, {}, Counts{2, 2, 1}); }).find("nodes"),
            std::string::npos);
  EXPECT_NE(message_of([&] { steady::steady_slab_lattice(m, nodes, {}, Counts{2, 2, 1}, 1.5); }).find("beam_ratio"),
            std::string::npos);
}

}  // namespace
