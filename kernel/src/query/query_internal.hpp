#pragma once
// Shared state of the ball-interference paths (lattice_query.cpp dispatches to query_naive.cpp,
// query_rangefinder.cpp and query_blocks.cpp; query_plan.cpp detects which apply).
#include <array>
#include <optional>
#include <cstdint>
#include <vector>

#include "query/element_evaluator.hpp"
#include "steady/core/progress.hpp"
#include "steady/query/interference.hpp"
#include "steady/query/lattice_query.hpp"

namespace steady::detail {

// Templates of every node and pattern for one group (i, j, 0) given the row prefixes (G W^dk V^(j+dj)).
struct QueryState;
struct GroupTemplates {
  std::vector<Ball> nodes;
  std::vector<Ball> beam_start, beam_end;
  void fill(const QueryState& q, const std::vector<SimilarityTransform>& prefix, std::int64_t i);
};

// The query paths' view of a lattice: for a steady brick in its own axes, power tables, block bounds and the
// plan of the fast paths; for any other layout only what the naive path needs (QueryPlan::steady_reason says
// why the others do not apply).
struct QueryState {
  const Lattice& lattice;
  ElementEvaluator eval;
  std::optional<BlockBounds> bounds;  // steady bricks only
  Ball bound;                 // contains the whole lattice
  double length_scale = 1.0;  // |bound.center| + bound.radius
  QueryPlan plan;
  std::vector<IndexBlock> pattern_starts;  // per pattern: the start groups where its beams can exist
  std::int64_t margin = 1;                 // largest |offset| of a beam pattern
  std::int64_t reach[3][2]{};              // smallest and largest di, dj, dk of the patterns (0 included)
  // Template-coordinate balls whose images bound each kind of element: per node its ball, per pattern
  // its two end balls (the beam's own radii when given).
  std::vector<Ball> node_templates, beam_start_templates, beam_end_templates;
  // World-space powers of the steps, X'^t = G X^t G^-1, to place candidates cheaply before the exact test.
  PowerTable world_u, world_v, world_w;
  // U^i applied to the template's node centers, and U^i's scale, for i in [-margin, u - 1 + margin]
  // (templates of rows and slabs are then one point transform away).
  std::vector<Vec3> u_nodes;
  std::vector<double> u_scales;
  // The distinct (dj, dk) offsets of the patterns, (0, 0) first, each pattern's offset, and the prefixes
  // G W^dk V^dj of the first slab (templates at (i, 0, 0) are one product away from them).
  std::vector<std::pair<int, int>> prefix_offsets;
  std::vector<int> pattern_prefix;
  std::vector<SimilarityTransform> slab_prefixes;
  GroupTemplates first_templates;  // the templates at (0, 0, 0)
  // Their extents under the O(1) path's maps (U, V, W), per node then per pattern: fixed for the lattice.
  struct TemplateExtents {
    std::array<Extent, kMaxRowMaps> u, v, w;
  };
  std::vector<TemplateExtents> constant_extents;
  Vec3 u_node(std::int64_t i, int n) const {
    const std::int64_t slot = i + margin;
    if (slot >= 0 && slot < static_cast<std::int64_t>(u_scales.size()))
      return u_nodes[static_cast<std::size_t>(slot * lattice.node_count() + n)];
    return eval.u().at(i).apply_point(lattice.definition().nodes[static_cast<std::size_t>(n)].center);
  }
  double u_scale(std::int64_t i) const {
    const std::int64_t slot = i + margin;
    if (slot >= 0 && slot < static_cast<std::int64_t>(u_scales.size())) return u_scales[static_cast<std::size_t>(slot)];
    return eval.u().at(i).scale;
  }

  explicit QueryState(const Lattice& lattice);
  void prepare_brick_paths();
  // Leaves only the naive path, with `reason` in the plan (block_bounds and forced methods refuse with it).
  void only_naive(const std::string& reason);
  // The inflated radius used for ranges and bounds (kQueryInflation, kQueryInflationPerStep).
  double inflation(const Ball& query) const;
};

inline void GroupTemplates::fill(const QueryState& q, const std::vector<SimilarityTransform>& prefix, std::int64_t i) {
  const Lattice& lat = q.lattice;
  const int nn = lat.node_count();
  nodes.resize(static_cast<std::size_t>(nn));
  const double s0 = prefix[0].scale * q.u_scale(i);
  for (int n = 0; n < nn; ++n)
    nodes[static_cast<std::size_t>(n)] = {prefix[0].apply_point(q.u_node(i, n)),
                                          s0 * q.node_templates[static_cast<std::size_t>(n)].radius};
  const auto& pats = lat.definition().beams;
  beam_start.resize(pats.size());
  beam_end.resize(pats.size());
  for (std::size_t p = 0; p < pats.size(); ++p) {
    const BeamPattern& b = pats[p];
    const SimilarityTransform& pe = prefix[static_cast<std::size_t>(q.pattern_prefix[p])];
    beam_start[p] = {nodes[static_cast<std::size_t>(b.from)].center, s0 * q.beam_start_templates[p].radius};
    beam_end[p] = {pe.apply_point(q.u_node(i + b.di, b.to)),
                   pe.scale * q.u_scale(i + b.di) * q.beam_end_templates[p].radius};
  }
}

// Working memory of one query, reused between queries of a thread. A filter can run a query inside a
// query (Lattice-in-Lattice), so each nesting depth leases its own.
struct BlockEntry {
  IndexBlock block;
  double spread[3];
  double gap;           // distance from the query to the block's union ball (visit order)
  double distance;      // from the query's center to that ball (pruning when the sink's reach shrinks)
  std::uint64_t kinds;  // kinds that may meet the query (all ones when not narrowed)
};
struct Scratch {
  IndexRanges is, js, ks;
  GroupTemplates templates;
  std::vector<Ball> ring_balls;
  std::vector<Extent> ring_extents;
  std::vector<char> ring_ready;
  std::vector<BlockEntry> stack;
};
class ScratchLease {
 public:
  ScratchLease();
  ~ScratchLease();
  ScratchLease(const ScratchLease&) = delete;
  ScratchLease& operator=(const ScratchLease&) = delete;
  Scratch& operator*() const { return *scratch_; }
  Scratch* operator->() const { return scratch_; }

 private:
  Scratch* scratch_;
};

// Tests candidates exactly and reports hits to the sink.
// A power of 2: a few microseconds of exact tests between two polls of the call's cancellation.
constexpr std::int64_t kPollCandidates = 256;

struct Probe {
  const QueryState& q;
  Ball query;     // the caller's ball: the exact tests
  Ball inflated;  // ranges and bounds
  HitSink& sink;
  bool stopped = false;
  std::int64_t candidates = 0;

  // The inflated radius, reduced to the sink's reach (plus the same inflation) when that is smaller.
  double pruning_radius() const {
    return std::min(inflated.radius, sink.reach() + (inflated.radius - query.radius));
  }

  // Each returns false once the sink has asked to stop; every kPollCandidates candidates the call may be
  // cancelled (Ctrl-C: a single query can test 10^9 of them).
  bool ball_geometry(const Ball& geometry, std::int64_t i, std::int64_t j, std::int64_t k, int n) {
    if ((++candidates & (kPollCandidates - 1)) == 0) poll_progress();
    const double d = distance_to_ball(query.center, geometry);
    if (!(d <= query.radius)) return true;
    const std::int64_t index = q.lattice.ball_index(NodeId{i, j, k, n});
    if (index < 0) return true;  // omitted
    ElementHit hit;
    hit.is_beam = false;
    hit.kind = n;
    hit.i = i, hit.j = j, hit.k = k;
    hit.index = index;
    hit.ball = geometry;
    hit.distance = d;
    if (!sink.on_hit(hit)) stopped = true;
    return !stopped;
  }
  bool beam_geometry(const BeamGeometry& geometry, std::int64_t i, std::int64_t j, std::int64_t k, int p) {
    if ((++candidates & (kPollCandidates - 1)) == 0) poll_progress();
    const double d = distance_to_beam(query.center, geometry);
    if (!(d <= query.radius)) return true;
    const std::int64_t index = q.lattice.beam_index(BeamId{i, j, k, p});
    if (index < 0) return true;  // an end is omitted
    ElementHit hit;
    hit.is_beam = true;
    hit.kind = p;
    hit.i = i, hit.j = j, hit.k = k;
    hit.index = index;
    hit.beam = geometry;
    hit.distance = d;
    if (!sink.on_hit(hit)) stopped = true;
    return !stopped;
  }
  bool ball(std::int64_t i, std::int64_t j, std::int64_t k, int n) {
    return ball_geometry(q.eval.node_ball(i, j, k, n), i, j, k, n);
  }
  bool ball_in_group(const SimilarityTransform& group, std::int64_t i, std::int64_t j, std::int64_t k, int n) {
    return ball_geometry(q.eval.node_ball(group, n), i, j, k, n);
  }
  bool beam(std::int64_t i, std::int64_t j, std::int64_t k, int p) {
    return beam_geometry(q.eval.beam(i, j, k, p), i, j, k, p);
  }
  // The same after a conservative pre-check on an approximate placement of the element (off by far less
  // than the inflation): most RangeFinder candidates are far from the query in the other directions.
  bool ball_near(const Ball& approx, std::int64_t i, std::int64_t j, std::int64_t k, int n) {
    if (distance_to_ball(inflated.center, approx) > inflated.radius) return true;
    return ball(i, j, k, n);
  }
  bool beam_near(const Ball& approx_start, const Ball& approx_end, std::int64_t i, std::int64_t j, std::int64_t k,
                 int p) {
    // The hull lies in the ball around its axis midpoint reaching both balls.
    const Vec3 mid = 0.5 * (approx_start.center + approx_end.center);
    const double reach = 0.5 * glm::length(approx_end.center - approx_start.center) +
                         std::max(approx_start.radius, approx_end.radius);
    if (glm::length(inflated.center - mid) > reach + inflated.radius) return true;
    return beam(i, j, k, p);
  }
};

void visit_naive(const QueryState& q, Probe& probe);
// `reject`: skip whole rows (slabs) by their invariants before RangeFinder (off: the paper's algorithm).
void visit_rows(const QueryState& q, Probe& probe, bool reject);
void visit_slabs(const QueryState& q, Probe& probe, bool reject);
void visit_constant(const QueryState& q, Probe& probe);
void visit_blocks(const QueryState& q, Probe& probe);

// A lower bound of the elements a query ball meets, before visiting any (result_estimate.cpp).
std::int64_t elements_surely_hit(const QueryState& q, const Ball& query);

// Fills q.plan (query_plan.cpp).
void detect_plan(QueryState& q);
// A ball containing every element, from every group's balls (any layout: O(groups)).
Ball bound_of_balls(const Lattice& lattice);

}  // namespace steady::detail
