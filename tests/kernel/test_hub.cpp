// Hub geometry: the circles where beam cones leave node spheres, tangent circles of the hull model, and
// incidence against a brute-force scan of all beams.
#include <gtest/gtest.h>

#include <random>

#include "steady/lattice/hub.hpp"
#include "test_support.hpp"
#include "brick_definition.hpp"

namespace steady {
namespace {

// A point on a circle at angle t.
Vec3 on_circle(const Circle& c, double t) {
  Vec3 u = glm::cross(c.normal, Vec3(1, 0, 0));
  if (glm::length(u) < 0.1) u = glm::cross(c.normal, Vec3(0, 1, 0));
  u = glm::normalize(u);
  const Vec3 v = glm::cross(c.normal, u);
  return c.center + c.radius * (std::cos(t) * u + std::sin(t) * v);
}

// Distance from p to the cone surface of the hull of two balls, measured as the difference between p's
// distance to the axis and the cone radius at p's axial position.
double off_cone(const BeamCone& c, const Vec3& p) {
  const double x = glm::dot(p - c.a, c.axis);
  const double rho = glm::length(p - c.a - x * c.axis);
  return rho - c.radius_at(x);
}

TEST(Hub, ExitCirclesLieOnSphereAndCone) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 a = test::random_vec(rng, 3.0), b = a + test::random_unit(rng) * (1.0 + 3.0 * u(rng));
    const double ra = 0.05 + 0.4 * u(rng), rb = 0.05 + 0.4 * u(rng);
    const BeamCone cone = beam_cone({a, ra}, {b, rb});
    ASSERT_TRUE(cone.has_lateral_surface());
    for (bool at_a : {true, false}) {
      const double r = at_a ? ra : rb;
      const double R = r * (1.0 + 1.5 * u(rng)) * (trial % 4 == 0 ? 0.0 : 1.0) + (trial % 4 == 0 ? r : 0.0);
      const double x = cone_exit_position(cone, at_a, R);
      const Vec3 center = at_a ? a + x * cone.axis : b - x * cone.axis;
      const Circle c{center, cone.axis, std::sqrt(R * R - x * x)};
      for (double t : {0.0, 1.0, 2.5, 4.0}) {
        const Vec3 p = on_circle(c, t);
        EXPECT_NEAR(glm::length(p - (at_a ? a : b)), R, 1e-12);
        EXPECT_NEAR(off_cone(cone, p), 0.0, 1e-12);
      }
    }
    // tangent circles: on the ball and on the cone, and the cone generator is orthogonal to the ball radius
    const Circle ta = cone.tangent_circle_a();
    const Vec3 p = on_circle(ta, 0.7);
    EXPECT_NEAR(glm::length(p - a), ra, 1e-12);
    EXPECT_NEAR(off_cone(cone, p), 0.0, 1e-12);
    const Vec3 q = on_circle(cone.tangent_circle_b(), 0.7);
    const Vec3 generator = q - p;  // same angle t: a generator line of the cone
    EXPECT_NEAR(glm::dot(generator, p - a) / glm::length(generator), 0.0, 1e-10);
  }
}

TEST(Hub, IncidenceMatchesBruteForce) {
  test::BrickDefinition d;
  d.nodes = {{{0, 0, 0}, 0.2}, {{0.5, 0.5, 0.5}, 0.15}};
  d.beams = {{0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0}, {0, 0, 0, 0, 1, 0.1, 0.1}, {1, 1, 1, 1, 0}};
  d.counts = {4, 3, 3};
  d.u = {Similarity::translation({1, 0, 0})};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::swirl(0.1, {0, 0, 1}, {-5, 0, 0}, 1.05)};
  d.omitted = {{1, 1, 1, 0}};
  const Lattice lat(d);
  for (std::int64_t index = 0; index < lat.ball_count(); ++index) {
    const NodeId node = lat.ball_id(index);
    const Hub h = hub(lat, node);
    std::size_t expected = 0;
    lat.for_each_beam([&](std::int64_t, const BeamId& id, const BeamGeometry&) {
      expected += (lat.beam_start(id) == node) + (lat.beam_end(id) == node);
    });
    EXPECT_EQ(h.stumps.size(), expected);
    for (const Stump& s : h.stumps) {
      EXPECT_NEAR(glm::length(s.cone.a - h.ball.center), 0.0, 1e-12);
      EXPECT_LE(glm::length(s.on_node.center - h.ball.center), h.ball.radius);
      EXPECT_LE(s.exit_position, s.cut_position);
      EXPECT_EQ(lat.beam_index(s.beam), s.beam_index);
    }
  }
}

}  // namespace
}  // namespace steady
