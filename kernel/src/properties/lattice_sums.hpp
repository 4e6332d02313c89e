#pragma once
// Internal: what the lattice sums share (lattice_properties.cpp, lattice_volume_model.cpp): the steps and the
// reference point in pre-placement coordinates, which patterns are steady along which direction, beam and hub
// geometry at any group placement, the border classes of a direction.
#include <atomic>
#include <set>
#include <tuple>
#include <string>
#include <vector>

#include "steady/core/errors.hpp"
#include "steady/properties/hub_properties.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/core/progress.hpp"
#include "steady/properties/similar_copies.hpp"

namespace steady::detail {

// Powers of a step cached at most (104 bytes each): enough for every row a sum enumerates in practice.
constexpr std::int64_t kMaxCachedPowers = 1'000'000;

// The start indices x with 0 <= x < count and 0 <= x + offset < count: [lo, hi).
struct IndexRange {
  std::int64_t lo = 0, hi = 0;
  std::int64_t size() const { return std::max<std::int64_t>(0, hi - lo); }
};
// A pattern's start groups along each direction (pattern_start_groups).
inline IndexRange range_i(const IndexBlock& b) { return {b.i0, b.i1}; }
inline IndexRange range_j(const IndexBlock& b) { return {b.j0, b.j1}; }
inline IndexRange range_k(const IndexBlock& b) { return {b.k0, b.k1}; }

// Beam patterns none of whose beams is in the lattice: each runs off the block or ends at an omitted node. Their
// geometry must not enter the sums at all (the series over the block, then the omitted nodes' beams subtracted): a
// dilation step can bring a pattern's two ends so close that one end ball holds the other, and such a pattern was
// refused although the lattice has no beam of it (found by fuzz_lattice_queries' 30-minute run; the brute force
// over the listed beams accepted it).
inline std::vector<char> patterns_without_beams(const Lattice& l) {
  const LatticeDefinition& def = l.definition();
  std::set<std::tuple<std::int64_t, std::int64_t, std::int64_t, int>> gone;
  for (const NodeId& id : def.omitted) gone.insert({id.i, id.j, id.k, id.n});
  std::vector<char> out(def.beams.size(), 0);
  for (std::size_t p = 0; p < def.beams.size(); ++p) {
    const BeamPattern& b = def.beams[p];
    const IndexBlock starts = pattern_start_groups(l.counts(), b);
    const IndexRange ri = range_i(starts), rj = range_j(starts), rk = range_k(starts);
    const double beams = double(ri.size()) * double(rj.size()) * double(rk.size());
    if (beams == 0.0) {
      out[p] = 1;
      continue;
    }
    if (beams > 2.0 * double(gone.size())) continue;  // more beams than the omitted nodes can end
    auto starts_at = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
      return i >= ri.lo && i < ri.hi && j >= rj.lo && j < rj.hi && k >= rk.lo && k < rk.hi;
    };
    std::set<std::tuple<std::int64_t, std::int64_t, std::int64_t>> killed;
    for (const auto& [i, j, k, node] : gone) {
      if (node == b.from && starts_at(i, j, k)) killed.insert({i, j, k});
      if (node == b.to && starts_at(i - b.di, j - b.dj, k - b.dk)) killed.insert({i - b.di, j - b.dj, k - b.dk});
    }
    out[p] = double(killed.size()) == beams;
  }
  return out;
}

// Everything the sums need, in pre-placement coordinates (group (i,j,k) is W^k V^j U^i; G comes last). The
// lattice must be its own steady brick (Lattice::brick_lattice()).
struct Context {
  const Lattice& lattice;
  const LatticeDefinition& def;
  const Counts& counts;
  Similarity G, U, V, W;
  Vec3 P{0.0};  // reference point, pre-placement
  bool uv = false, uw = false, vw = false;  // pairs that commute exactly
  HubPropertiesOptions hub_options;
  Progress* progress = &no_progress();  // advanced once per beam row and hub class
  mutable std::atomic<std::int64_t> beam_shapes{0}, hub_shapes{0}, overlapping{0};
  std::vector<char> absent;  // patterns_without_beams: left out of every sum and every hub

  explicit Context(const Lattice& l)
      : lattice(l), def(l.definition()), counts(l.counts()), G(brick_of(l).placement), U(brick_of(l).steps[0]),
        V(brick_of(l).steps[1]), W(brick_of(l).steps[2]) {
    uv = exactly_commute(U, V);
    uw = exactly_commute(U, W);
    vw = exactly_commute(V, W);
    cache_powers();
    P = group(counts.u / 2, counts.v / 2, counts.w / 2).apply_point(def.nodes[0].center);
    absent = patterns_without_beams(l);
  }
  static const SteadyBrick& brick_of(const Lattice& l) {
    const SteadyBrick* brick = l.layout().steady_brick();
    if (!brick || brick->reordered()) fail_input("lattice", "the closed-form sums need a steady brick in its own axes");
    return *brick;
  }
  // Powers of the steps as matrices, cached for the indices the sums visit (every group and its neighbours
  // for U and V, the pattern offsets for W): the sums compose them instead of exponentiating generators.
  std::int64_t reach = 0;
  std::vector<SimilarityTransform> u_powers, v_powers, w_powers;  // index + reach
  static SimilarityTransform cached(const Similarity& s, const std::vector<SimilarityTransform>& cache,
                                    std::int64_t reach, std::int64_t n) {
    const std::int64_t at = n + reach;
    if (at >= 0 && at < static_cast<std::int64_t>(cache.size())) return cache[at];
    return s.power(static_cast<double>(n)).transform();
  }
  SimilarityTransform u_pow(std::int64_t i) const { return cached(U, u_powers, reach, i); }
  SimilarityTransform v_pow(std::int64_t j) const { return cached(V, v_powers, reach, j); }
  SimilarityTransform w_pow(std::int64_t k) const { return cached(W, w_powers, reach, k); }
  void cache_powers() {
    for (const BeamPattern& b : def.beams) reach = std::max<std::int64_t>({reach, std::abs(b.di), std::abs(b.dj), std::abs(b.dk)});
    auto fill = [this](const Similarity& s, std::vector<SimilarityTransform>& cache, std::int64_t count) {
      if (count + 2 * reach > kMaxCachedPowers) return;  // rows this long are summed in closed form anyway
      cache.resize(static_cast<std::size_t>(count + 2 * reach));
      for (std::int64_t n = -reach; n < count + reach; ++n) cache[n + reach] = s.power(static_cast<double>(n)).transform();
    };
    fill(U, u_powers, counts.u);
    fill(V, v_powers, counts.v);
    fill(W, w_powers, 1);
  }
  // W^k V^j U^i for any integers (outside the lattice too: virtual neighbours of border groups): the placement
  // formula without G (the sums place their totals by G once, in finish()).
  SimilarityTransform group(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return SteadyBrick::place(SteadyBrick::row_prefix(SimilarityTransform{}, w_pow(k), v_pow(j)), u_pow(i));
  }
  SimilarityTransform about_P(const SimilarityTransform& t) const { return transform_about(t, P); }
  bool j_steady(const BeamPattern& b) const { return b.dk == 0 || vw; }
  bool i_steady(const BeamPattern& b) const {
    return j_steady(b) && (b.dj == 0 || uv) && (b.dk == 0 || uw);
  }
};

inline MassMoments shifted(const MassMoments& m, const Vec3& by) {
  SimilarityTransform t;
  t.translation = by;
  return transformed(m, t);
}

inline Ball node_ball(const Context& c, const SimilarityTransform& t, int n) {
  const TemplateNode& node = c.def.nodes[n];
  return {t.apply_point(node.center), t.scale * node.radius};
}

[[noreturn]] inline void fail_beam(int pattern, const std::string& what) {
  fail_input("beams[" + std::to_string(pattern) + "]", what + ": the lattice is not clean there");
}

// The beam of pattern p from the group placed by ta to the group placed by tb: both stumps, each as if
// alone, as moments about P.
inline MassMoments beam_moments(const Context& c, const SimilarityTransform& ta, const SimilarityTransform& tb, int p) {
  const BeamPattern& b = c.def.beams[p];
  const Ball A = node_ball(c, ta, b.from), B = node_ball(c, tb, b.to);
  const double ra = b.has_radii() ? *b.from_radius * ta.scale : A.radius;
  const double rb = b.has_radii() ? *b.to_radius * tb.scale : B.radius;
  const Vec3 d = B.center - A.center;
  const double L = glm::length(d);
  if (!(std::abs(ra - rb) < L)) fail_beam(p, "one end ball of a beam contains the other");
  const Vec3 axis = d / L;
  // As in validate_hub_shape: a node ball may cross the mid-plane (its cap beyond lies inside the cone, and the
  // hub ends at the cut) as long as the beam leaves the ball before the mid-plane.
  const HubStump at_a{axis, L, ra, rb, 0.0}, at_b{-axis, L, rb, ra, 0.0};
  if (!(0.5 * L > stump_cap(A.radius, at_a).exit_position * (1.0 + kMidPlaneSlack)) ||
      !(0.5 * L > stump_cap(B.radius, at_b).exit_position * (1.0 + kMidPlaneSlack)))
    fail_beam(p, "a node ball holds the beam's whole mid-plane disk");
  const double sin_phi = (ra - rb) / L;
  if (L + rb * sin_phi < 0.5 * L || L - ra * sin_phi < 0.5 * L)
    fail_beam(p, "a beam end ball crosses the beam's mid-plane");
  ++c.beam_shapes;
  return shifted(stump_contribution_alone(A.radius, at_a).moments, A.center - c.P) +
         shifted(stump_contribution_alone(B.radius, at_b).moments, B.center - c.P);
}

// A stump of node n's hub: its pattern, which end of it n is, and the offset to the other group.
struct Incidence {
  int pattern = 0;
  bool at_start = true;
  int di = 0, dj = 0, dk = 0;
};

inline std::vector<Incidence> incidences(const Context& c, int node) {
  std::vector<Incidence> out;
  for (int p = 0; p < static_cast<int>(c.def.beams.size()); ++p) {
    if (c.absent[p]) continue;
    const BeamPattern& b = c.def.beams[p];
    if (b.from == node) out.push_back({p, true, b.di, b.dj, b.dk});
    if (b.to == node) out.push_back({p, false, -b.di, -b.dj, -b.dk});
  }
  return out;
}

// Node n's hub placed by `base`, with the stumps `present` whose other groups are placed by `other`.
inline HubShape hub_shape_at(const Context& c, int node, const SimilarityTransform& base, const std::vector<Incidence>& present,
                      const std::vector<SimilarityTransform>& other) {
  HubShape h;
  const Ball ball = node_ball(c, base, node);
  h.center = ball.center;
  h.radius = ball.radius;
  for (std::size_t k = 0; k < present.size(); ++k) {
    const BeamPattern& b = c.def.beams[present[k].pattern];
    const int far_node = present[k].at_start ? b.to : b.from;
    const Ball far = node_ball(c, other[k], far_node);
    const Vec3 d = far.center - ball.center;
    const double L = glm::length(d);
    double r = ball.radius, r_far = far.radius;
    if (b.has_radii()) {
      r = (present[k].at_start ? *b.from_radius : *b.to_radius) * base.scale;
      r_far = (present[k].at_start ? *b.to_radius : *b.from_radius) * other[k].scale;
    }
    h.stumps.push_back({d / L, L, r, r_far});
  }
  return h;
}

// The classes of one direction: border indices alone, the interior as one range when the direction is
// steady for the hub (else every index alone).
struct IndexClass {
  std::int64_t first = 0, count = 1;
};
inline std::vector<IndexClass> index_classes(std::int64_t n, int reach, bool steady) {
  std::vector<IndexClass> out;
  if (!steady || n <= 2 * static_cast<std::int64_t>(reach) + 1) {
    for (std::int64_t i = 0; i < n; ++i) out.push_back({i, 1});
    return out;
  }
  for (std::int64_t i = 0; i < reach; ++i) out.push_back({i, 1});
  out.push_back({reach, n - 2 * reach});
  for (std::int64_t i = n - reach; i < n; ++i) out.push_back({i, 1});
  return out;
}

inline bool in_lattice(std::int64_t x, int offset, std::int64_t count) { return x + offset >= 0 && x + offset < count; }

// The hub of an actual node (i, j, k, n) at its actual place, with the stumps whose other group exists,
// all of them (`generic`, as if nothing were omitted) or only those whose beams exist.
inline HubShape actual_hub(const Context& c, const NodeId& id, bool generic) {
  const Counts& n = c.counts;
  std::vector<Incidence> present;
  std::vector<SimilarityTransform> other;
  for (const Incidence& s : incidences(c, id.n)) {
    if (!in_lattice(id.i, s.di, n.u) || !in_lattice(id.j, s.dj, n.v) || !in_lattice(id.k, s.dk, n.w)) continue;
    if (!generic) {
      const BeamPattern& b = c.def.beams[s.pattern];
      const BeamId beam = s.at_start ? BeamId{id.i, id.j, id.k, s.pattern}
                                     : BeamId{id.i - b.di, id.j - b.dj, id.k - b.dk, s.pattern};
      if (!c.lattice.beam_exists(beam)) continue;
    }
    present.push_back(s);
    other.push_back(c.group(id.i + s.di, id.j + s.dj, id.k + s.dk));
  }
  return hub_shape_at(c, id.n, c.group(id.i, id.j, id.k), present, other);
}


}  // namespace steady::detail
