#pragma once
// Lattices shared by the clean-check, B-rep and trimming tests: strut lattices with explicit beam radii whose
// steps are translations, swirls, screws or general similarities close to a unit step.
#include <random>

#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice.hpp"
#include "test_support.hpp"
#include "brick_definition.hpp"

namespace steady::test {

enum class StepKind { Translation, Swirl, Screw, General };

// A cubic strut lattice (one node per group, beams along the three steps) with node radius `node_radius` in
// template units and beam radii drawn in [0.3, 0.6] * node_radius (exit caps of at most 37 degrees, disjoint at
// 90 degrees with room for the distortion of the steps); the steps
// are near-unit steps of the given kind, so the lattice is clean for node radii up to about 0.3.
inline Lattice strut_lattice(std::mt19937_64& rng, StepKind kind, Counts counts, double node_radius = 0.25) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  auto beam_radius = [&] { return node_radius * (0.3 + 0.3 * u01(rng)); };
  test::BrickDefinition d;
  d.nodes = {{{0, 0, 0}, node_radius}};
  for (int axis = 0; axis < 3; ++axis) {
    BeamPattern p{0, axis == 0, axis == 1, axis == 2, 0, beam_radius(), beam_radius()};
    d.beams.push_back(p);
  }
  d.counts = counts;
  const Vec3 e[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Similarity steps[3];
  for (int a = 0; a < 3; ++a) {
    switch (kind) {
      case StepKind::Translation: steps[a] = Similarity::translation(e[a] + random_vec(rng, 0.1)); break;
      case StepKind::Swirl: {
        // A swirl about a far axis orthogonal to e[a] moves the origin by about one unit along e[a].
        const Vec3 axis = glm::normalize(glm::cross(e[a], random_unit(rng)));
        const double angle = 0.05 + 0.05 * u01(rng);
        const Vec3 center = glm::cross(axis, e[a]) / angle;
        steps[a] = Similarity::swirl(angle, axis, center, std::exp(0.03 * (2 * u01(rng) - 1)));
        break;
      }
      case StepKind::Screw: {
        const double angle = 0.1 * (2 * u01(rng) - 1);
        steps[a] = Similarity::screw(angle, e[a], random_vec(rng, 0.5), 1.0);
        break;
      }
      case StepKind::General: {
        // One draw per statement: the order in which a call's arguments are evaluated is up to the compiler
        // (GCC and clang differ), and the sample must be the same whatever builds the tests. The order is GCC's
        // (last argument first), which the tests' expectations were measured with.
        const double scale = std::exp(0.02 * (2 * u01(rng) - 1));
        const Vec3 center = random_vec(rng, 1.0);
        const Vec3 axis = random_unit(rng);
        const double angle = 0.04 * (2 * u01(rng) - 1);
        steps[a] = Similarity::swirl(angle, axis, center, scale) * Similarity::translation(e[a]);
        break;
      }
    }
  }
  d.u = {steps[0]};
  d.v = {steps[1]};
  d.w = {steps[2]};
  const double scale = 0.5 + 2.0 * u01(rng);  // drawn in GCC's order too (see above)
  const Vec3 turn_point = random_vec(rng, 2.0);
  const Vec3 turn_axis = random_unit(rng);
  const double turn = u01(rng) * 3.0;
  d.placement = Similarity::rotation(turn, turn_axis, turn_point) * Similarity::dilation(scale, Vec3(0.0));
  return Lattice(std::move(d));
}

// A body-centred cubic strut lattice: corner node and centre node, eight diagonals; radii as above.
inline Lattice bcc_lattice(std::mt19937_64& rng, Counts counts, double corner_radius = 0.2, double center_radius = 0.2) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  test::BrickDefinition d;
  d.nodes = {{{0, 0, 0}, corner_radius}, {{0.5, 0.5, 0.5}, center_radius}};
  const double r = 0.06 + 0.02 * u01(rng);
  for (int di = 0; di <= 1; ++di)
    for (int dj = 0; dj <= 1; ++dj)
      for (int dk = 0; dk <= 1; ++dk) d.beams.push_back({1, di, dj, dk, 0, r, r});
  d.counts = counts;
  d.u = {Similarity::translation({1, 0, 0})};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::translation({0, 0, 1})};
  return Lattice(std::move(d));
}

// An axis-aligned cubic strut lattice: nodes at integer points of [0, n)^3, beams along x, y, z with end radii
// that differ (general cones).
inline FlatLattice grid_lattice(int n, double node_radius = 0.25) {
  std::vector<Ball> balls;
  std::vector<FlatBeam> beams;
  auto id = [&](int i, int j, int k) { return (k * n + j) * n + i; };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) balls.push_back({{double(i), double(j), double(k)}, node_radius});
  const double radii[3][2] = {{0.10, 0.12}, {0.11, 0.09}, {0.08, 0.10}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (i + 1 < n) beams.push_back({id(i, j, k), id(i + 1, j, k), radii[0][0], radii[0][1]});
        if (j + 1 < n) beams.push_back({id(i, j, k), id(i, j + 1, k), radii[1][0], radii[1][1]});
        if (k + 1 < n) beams.push_back({id(i, j, k), id(i, j, k + 1), radii[2][0], radii[2][1]});
      }
  return make_flat_lattice(balls, beams);
}

}  // namespace steady::test
