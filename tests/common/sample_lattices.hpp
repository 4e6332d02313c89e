#pragma once
// Sample lattices shared by the kernel tests and the benchmarks: the papers' benchmark classes (regular,
// sheared regular, cylindrical, bent-twisted-tapered) at any counts, and seeded random steady bricks of every
// kind of step.
#include <random>
#include <string>
#include <vector>

#include "steady/lattice/lattice.hpp"
#include "test_support.hpp"
#include "brick_definition.hpp"
#include "steady/core/constants.hpp"

namespace steady::test {


// Body-centred cubic template: corner node 0, center node 1, 14 patterns (3 corner edges, 3 center
// edges, 8 corner-center diagonals): the papers' fine lattices have 2 balls and 14 edge patterns.
inline std::vector<BeamPattern> bcc_patterns(bool radii = false) {
  std::vector<BeamPattern> p = {{0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0}, {1, 1, 0, 0, 1},
                                {1, 0, 1, 0, 1}, {1, 0, 0, 1, 1}, {0, 0, 0, 0, 1}, {1, 1, 0, 0, 0},
                                {1, 0, 1, 0, 0}, {1, 0, 0, 1, 0}, {1, 1, 1, 0, 0}, {1, 1, 0, 1, 0},
                                {1, 0, 1, 1, 0}, {1, 1, 1, 1, 0}};
  if (radii)
    for (auto& b : p) {
      b.from_radius = 0.04;
      b.to_radius = 0.03;
    }
  return p;
}

inline std::vector<BeamPattern> cubic_patterns() { return {{0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0}}; }

// Radii in units of the spacing.
inline Lattice regular_bcc(Counts counts, double spacing = 1.0, double corner_radius = 0.08, double center_radius = 0.06) {
  const double s = spacing;
  return Lattice::incremental({{{0, 0, 0}, corner_radius * s}, {{0.5 * s, 0.5 * s, 0.5 * s}, center_radius * s}},
                              bcc_patterns(), counts, Similarity::translation({s, 0, 0}),
                              Similarity::translation({0, s, 0}), Similarity::translation({0, 0, s}));
}

// The cubic template (one node, three patterns) on a regular grid.
inline Lattice regular_cubic(Counts counts, double spacing, double radius) {
  return Lattice::incremental({{{0, 0, 0}, radius}}, cubic_patterns(), counts, Similarity::translation({spacing, 0, 0}),
                              Similarity::translation({0, spacing, 0}), Similarity::translation({0, 0, spacing}));
}

// Non-orthogonal translations: the paper's O(1) conditions fail, the dual-direction maps do not.
inline Lattice sheared_cubic(Counts counts) {
  return Lattice::incremental({{{0, 0, 0}, 0.1}}, cubic_patterns(), counts, Similarity::translation({1, 0, 0}),
                              Similarity::translation({0.4, 1, 0}), Similarity::translation({0.2, -0.3, 1}));
}

// Cylindrical: i radial (dilation about a point of the axis), j around the axis, k along it; square cells
// (radial step = arc step). The axial step is the arc step of the first ring, or of the middle ring when
// `middle_cells`; radii in units of the first ring's arc step. One node (cubic patterns) or two (bcc).
inline Lattice cylindrical(Counts counts, double inner_radius, int nodes, bool middle_cells, double corner_radius,
                           double center_radius) {
  const double dtheta = 2 * kPi / static_cast<double>(counts.v);
  const double d = 1.0 + dtheta;
  const double arc = inner_radius * dtheta;
  const double a = middle_cells ? arc * std::pow(d, 0.5 * static_cast<double>(counts.u - 1)) : arc;
  std::vector<TemplateNode> t = {{{inner_radius, 0, 0}, corner_radius * arc}};
  if (nodes == 2) t.push_back({{inner_radius * std::sqrt(d), 0, 0.5 * a}, center_radius * arc});
  return Lattice::incremental(t, nodes == 2 ? bcc_patterns() : cubic_patterns(), counts,
                              Similarity::dilation(d, {0, 0, 0}), Similarity::rotation(dtheta, {0, 0, 1}, {0, 0, 0}),
                              Similarity::translation({0, 0, a}));
}
inline Lattice cylindrical_bcc(Counts counts, double inner_radius = 10.0) {
  return cylindrical(counts, inner_radius, 2, false, 0.08, 0.06);
}

// Bent, twisted and tapered: swirl U (bend + taper), screw V (twist), swirl W, cumulative over the counts.
// Issue 14's scale lattice (bench_brep's part 2, bench_step_with_skin.py): one node of radius 0.25 and three beams
// of unequal end radii a unit cell, U a slight swirl (graded), V and W translations.
inline Lattice swirled_scale_lattice(Counts counts) {
  BrickDefinition d;
  d.nodes = {{{0, 0, 0}, 0.25}};
  const double radii[3][2] = {{0.10, 0.12}, {0.11, 0.09}, {0.08, 0.10}};
  for (int k = 0; k < 3; ++k) d.beams.push_back({0, k == 0, k == 1, k == 2, 0, radii[k][0], radii[k][1]});
  d.counts = counts;
  d.u = {Similarity::swirl(0.004, {0, 0, 1}, {0, -250, 0}, 1.0005)};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::translation({0, 0, 1})};
  return Lattice(std::move(d));
}

inline Lattice bent_twisted_tapered(Counts counts, double spacing = 1.0, double radius = 0.12) {
  const double lu = spacing * static_cast<double>(counts.u - 1), lv = spacing * static_cast<double>(counts.v - 1),
               lw = spacing * static_cast<double>(counts.w - 1);
  const Similarity U = Similarity::swirl(0.5 * kPi, {0, 1, 0}, {0, 0, 1.2 * lu + 10.0}, 0.7);
  const Similarity V = Similarity::screw(0.25 * kPi, {0, 1, 0}, {0.5 * lu, 0, 0.5 * lw}, lv);
  const Similarity W = Similarity::swirl(0.3 * kPi, {0, 0, 1}, {0.5 * lu, 0.5 * lv, -lw}, 1.3);
  return Lattice::interpolating({{{0, 0, 0}, radius * spacing}}, cubic_patterns(), counts, U, V, W);
}

struct RandomLatticeOptions {
  std::int64_t max_count = 5;
  bool omit = true;
  bool radii = true;
};

// A random steady brick: 1 to 3 nodes, 1 to 6 patterns with offsets in [-1, 2], random steps of every
// kind (small angles and scales so that groups stay apart), random placement, some omitted nodes.
inline Lattice random_lattice(std::mt19937_64& rng, int index, RandomLatticeOptions opt = {}) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  auto count = [&] { return 1 + static_cast<std::int64_t>(u01(rng) * opt.max_count); };
  const int nodes = 1 + static_cast<int>(u01(rng) * 3);
  std::vector<TemplateNode> tn;
  for (int n = 0; n < nodes; ++n) tn.push_back({random_vec(rng, 0.4), 0.05 + 0.15 * u01(rng)});
  std::vector<BeamPattern> pats;
  const int np = 1 + static_cast<int>(u01(rng) * 6);
  for (int p = 0; p < np && pats.size() < 6; ++p) {
    BeamPattern b;
    b.from = static_cast<int>(u01(rng) * nodes);
    b.to = static_cast<int>(u01(rng) * nodes);
    b.di = static_cast<int>(std::floor(u01(rng) * 4)) - 1;
    b.dj = static_cast<int>(std::floor(u01(rng) * 3)) - 1;
    b.dk = static_cast<int>(std::floor(u01(rng) * 3)) - 1;
    if (b.di == 0 && b.dj == 0 && b.dk == 0 && b.from == b.to) continue;
    if (b.di == 0 && b.dj == 0 && b.dk == 0 && tn[b.from].center == tn[b.to].center) continue;
    bool dup = false;
    for (const auto& o : pats)
      dup |= (o.from == b.from && o.to == b.to && o.di == b.di && o.dj == b.dj && o.dk == b.dk) ||
             (o.from == b.to && o.to == b.from && o.di == -b.di && o.dj == -b.dj && o.dk == -b.dk);
    if (dup) continue;
    if (opt.radii && u01(rng) < 0.3) {
      b.from_radius = tn[b.from].radius * (0.3 + 0.7 * u01(rng));
      b.to_radius = tn[b.to].radius * (0.3 + 0.7 * u01(rng));
    }
    pats.push_back(b);
  }
  // Steps: a unit-ish translation composed with a random similarity of kind `kind` (small).
  auto step = [&](const Vec3& along, int kind) {
    const double angle = (2 * u01(rng) - 1) * 0.6;
    const double scale = std::exp((2 * u01(rng) - 1) * 0.15);
    const Vec3 axis = random_unit(rng), point = random_vec(rng, 3.0);
    switch (kind % 7) {
      case 0: return Similarity::translation(along + random_vec(rng, 0.2));
      case 1: return Similarity::rotation(angle, axis, point + along * 4.0);
      case 2: return Similarity::screw(angle, axis, point, 1.2);
      case 3: return Similarity::dilation(1.0 + 0.2 * u01(rng), point - along * 5.0);
      case 4: return Similarity::swirl(angle, axis, point, scale);
      case 5: return Similarity::translation(along) * Similarity::swirl(0.3 * angle, axis, point, std::sqrt(scale));
      default:  // near-identity screw composed with a translation
        return Similarity::translation(along) * Similarity::rotation(1e-7 * angle, axis, point);
    }
  };
  const Counts counts{count(), count(), count()};
  const Similarity U = step({1.2, 0, 0}, index), V = step({0, 1.2, 0}, index / 7), W = step({0, 0, 1.2}, index / 49);
  const Similarity G = random_similarity(rng, index);
  test::BrickDefinition d;
  d.nodes = tn;
  d.beams = pats;
  d.counts = counts;
  d.u = {U, StepControl::Incremental};
  d.v = {V, StepControl::Incremental};
  d.w = {W, StepControl::Incremental};
  d.placement = G;
  if (opt.omit && u01(rng) < 0.5) {
    const int omitted = static_cast<int>(u01(rng) * 4);
    for (int o = 0; o < omitted; ++o)
      d.omitted.push_back({static_cast<std::int64_t>(u01(rng) * counts.u), static_cast<std::int64_t>(u01(rng) * counts.v),
                           static_cast<std::int64_t>(u01(rng) * counts.w), static_cast<int>(u01(rng) * nodes)});
  }
  return Lattice(std::move(d));
}

}  // namespace steady::test
