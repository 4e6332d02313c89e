#pragma once
// Random small lattices for the property tests: steps close to unit translations (so beams stay long
// compared with the balls), of every kind, with borders, both beam models and omitted nodes.
#include <random>
#include <string>

#include "steady/lattice/lattice.hpp"
#include "steady/lattice/presets.hpp"
#include "test_support.hpp"
#include "brick_definition.hpp"

namespace steady::test {

enum class StepKind { Translations, TranslationsVW, General };

// A step near translation by `dir`: composed with a small swirl/screw unless `translation_only`.
inline Similarity near_translation(std::mt19937_64& rng, const Vec3& dir, bool translation_only) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Similarity t = Similarity::translation(dir + 0.1 * random_vec(rng));
  if (translation_only) return t;
  const double angle = 0.15 * u(rng), scale = std::exp(0.04 * u(rng));
  return Similarity::swirl(angle, random_unit(rng), random_vec(rng, 3.0), scale) * t;
}

struct LatticeOptions {
  StepKind steps = StepKind::General;
  bool hull_model = false;
  int nodes = 2;
  int patterns = 5;
  int max_offset = 1;
  int omitted = 0;
};

inline Lattice random_lattice(std::mt19937_64& rng, const LatticeOptions& o, Counts counts) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::uniform_int_distribution<int> offset(-o.max_offset, o.max_offset);
  test::BrickDefinition d;
  for (int n = 0; n < o.nodes; ++n)
    d.nodes.push_back({n == 0 ? Vec3(0.0) : Vec3(0.5, 0.5, 0.5) + 0.15 * random_vec(rng), 0.12 + 0.06 * u01(rng)});
  while (static_cast<int>(d.beams.size()) < o.patterns) {
    BeamPattern b;
    b.from = std::uniform_int_distribution<int>(0, o.nodes - 1)(rng);
    b.to = std::uniform_int_distribution<int>(0, o.nodes - 1)(rng);
    b.di = offset(rng);
    b.dj = offset(rng);
    b.dk = offset(rng);
    if (b.di == 0 && b.dj == 0 && b.dk == 0 && b.from == b.to) continue;
    bool duplicate = false;
    for (const auto& e : d.beams)
      duplicate = duplicate || (e.from == b.from && e.to == b.to && e.di == b.di && e.dj == b.dj && e.dk == b.dk) ||
                  (e.from == b.to && e.to == b.from && e.di == -b.di && e.dj == -b.dj && e.dk == -b.dk);
    if (duplicate) continue;
    if (!o.hull_model) {
      b.from_radius = d.nodes[b.from].radius * (0.4 + 0.5 * u01(rng));
      b.to_radius = d.nodes[b.to].radius * (0.4 + 0.5 * u01(rng));
    }
    d.beams.push_back(b);
  }
  d.counts = counts;
  const bool all = o.steps == StepKind::Translations;
  d.u = {near_translation(rng, Vec3(1, 0, 0), all)};
  d.v = {near_translation(rng, Vec3(0, 1, 0), all || o.steps == StepKind::TranslationsVW)};
  d.w = {near_translation(rng, Vec3(0, 0, 1), all || o.steps == StepKind::TranslationsVW)};
  d.placement = random_similarity(rng, 5);
  for (int k = 0; k < o.omitted; ++k)
    d.omitted.push_back({std::uniform_int_distribution<std::int64_t>(0, counts.u - 1)(rng),
                         std::uniform_int_distribution<std::int64_t>(0, counts.v - 1)(rng),
                         std::uniform_int_distribution<std::int64_t>(0, counts.w - 1)(rng),
                         std::uniform_int_distribution<int>(0, o.nodes - 1)(rng)});
  return Lattice(d);
}

// Two nodes close together with beams along U and V (bent, slightly tapered): balls and beams of neighbouring
// hubs overlap in varying ways, sometimes in one cluster of overlapping hubs, sometimes in several. Beam radii are
// drawn from [beam, beam + beam_span); `count_u` cells along U.
inline BrickDefinition two_close_nodes(std::mt19937_64& rng, double beam, double beam_span, std::int64_t count_u) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  BrickDefinition d;
  const double r0 = 0.2 + 0.1 * unit(rng), r1 = 0.15 + 0.1 * unit(rng);
  d.nodes = {{Vec3(0.0), r0}, {Vec3(0.3 + 0.2 * unit(rng), 0.3 + 0.2 * unit(rng), 0.1 * unit(rng)), r1}};
  const double b = beam + beam_span * unit(rng);
  d.beams = {{0, 1, 0, 0, 0, b, b}, {0, 0, 1, 0, 0, b, 0.9 * b}, {0, 1, 0, 0, 1, b, b}, {1, 0, 1, 0, 0, b, b}};
  d.counts = {count_u, 2, 1};
  d.u = {Similarity::swirl(0.04 * unit(rng), {0, 0, 1}, {0.5, -6, 0}, 1.0 + 0.03 * unit(rng)) *
         Similarity::translation({1, 0, 0})};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::translation({0, 0, 1})};
  return d;
}

// A preset cell (cells of 1) with nodes `node_fraction` of its neighbour distance and every beam `beam_ratio` of
// its node radius, `counts` cells, translation steps (callers replace the ones they grade): the crowded sweep's
// designs (tests/python/crowded_sweep.py).
inline BrickDefinition preset_brick(const std::string& name, double node_fraction, double beam_ratio,
                                    const Counts& counts) {
  const PresetCell& cell = preset_cell(name);
  const double node = node_fraction * cell.neighbour_distance;
  BrickDefinition d;
  for (const Vec3& b : cell.basis) d.nodes.push_back({b, node});
  for (BeamPattern p : preset_beam_patterns(cell)) {
    p.from_radius = p.to_radius = beam_ratio * node;
    d.beams.push_back(p);
  }
  d.counts = counts;
  d.u = {Similarity::translation({1, 0, 0})};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::translation({0, 0, 1})};
  return d;
}

}  // namespace steady::test
