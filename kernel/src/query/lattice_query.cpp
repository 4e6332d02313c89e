#include "steady/query/lattice_query.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "query/hit_sinks.hpp"
#include "query/query_internal.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/numeric_range.hpp"
#include "steady/query/becots_query.hpp"
#include "steady/query/query_tolerance.hpp"

namespace steady {

const char* to_string(QueryMethod method) {
  switch (method) {
    case QueryMethod::Auto: return "auto";
    case QueryMethod::Naive: return "naive";
    case QueryMethod::Rows: return "rows";
    case QueryMethod::Slabs: return "slabs";
    case QueryMethod::Constant: return "constant";
    case QueryMethod::Blocks: return "blocks";
    case QueryMethod::PaperRows: return "rows-paper";
    case QueryMethod::PaperSlabs: return "slabs-paper";
    case QueryMethod::Becots: return "becots";
  }
  return "unknown";
}

QueryMethod query_method_from_string(const std::string& name, const std::string& field) {
  for (QueryMethod m : {QueryMethod::Auto, QueryMethod::Naive, QueryMethod::Rows, QueryMethod::Slabs,
                        QueryMethod::Constant, QueryMethod::Blocks, QueryMethod::PaperRows, QueryMethod::PaperSlabs,
                        QueryMethod::Becots})
    if (name == to_string(m)) return m;
  fail_input(field, "unknown query method '" + name +
                        "' (auto, naive, rows, slabs, constant, blocks, rows-paper, slabs-paper, becots)");
}

void validate_query_ball(const Ball& query, const std::string& field) {
  // The common case without building any message.
  const Vec3& c = query.center;
  if (std::abs(c.x) <= kMaxCoordinate && std::abs(c.y) <= kMaxCoordinate && std::abs(c.z) <= kMaxCoordinate &&
      query.radius >= 0.0 && query.radius <= kMaxQueryRadius)
    return;
  require_within(query.center, kMaxCoordinate, field + ".center");
  require_within(query.radius, kMaxQueryRadius, field + ".radius");
  if (query.radius < 0.0) fail_input(field + ".radius", "must be >= 0 (got " + std::to_string(query.radius) + ")");
}

namespace detail {

namespace {
std::int64_t largest_offset(const Lattice& lattice) {
  std::int64_t m = 1;
  for (const BeamPattern& b : lattice.definition().beams)
    m = std::max<std::int64_t>({m, std::abs(b.di), std::abs(b.dj), std::abs(b.dk)});
  return m;
}
}  // namespace

QueryState::QueryState(const Lattice& lat) : lattice(lat), eval(lat, largest_offset(lat)), margin(largest_offset(lat)) {
  const Counts& c = lat.counts();
  const auto& nodes = lat.definition().nodes;
  for (const auto& n : nodes) node_templates.push_back({n.center, n.radius});
  for (const BeamPattern& b : lat.definition().beams) {
    const auto& a = nodes[static_cast<std::size_t>(b.from)];
    const auto& e = nodes[static_cast<std::size_t>(b.to)];
    beam_start_templates.push_back({a.center, b.has_radii() ? *b.from_radius : a.radius});
    beam_end_templates.push_back({e.center, b.has_radii() ? *b.to_radius : e.radius});
    const int d[3] = {b.di, b.dj, b.dk};
    for (int a = 0; a < 3; ++a) {
      reach[a][0] = std::min<std::int64_t>(reach[a][0], d[a]);
      reach[a][1] = std::max<std::int64_t>(reach[a][1], d[a]);
    }
    pattern_starts.push_back(pattern_start_groups(c, b));
  }
  if (eval.steady()) {
    bounds.emplace(lat, margin);
    bound = bounds->lattice_bound();
    length_scale = glm::length(bound.center) + bound.radius;
    try {
      prepare_brick_paths();
    } catch (const InvalidInput& e) {
      // The fast paths tabulate the steps' powers over the lattice's groups and a margin beyond them, as far as
      // a pattern's far end can reach. A steep dilation can take such a power, for a group that does not exist,
      // out of the numerical range (found by fuzz_lattice_json: a scale of 150 a step and a pattern offset of 9
      // on 4 groups); every element of the lattice is in range, so the naive path answers (a small lattice).
      only_naive("a power of the steps that the fast paths tabulate beyond the lattice's groups is out of range (" +
                 std::string(e.what()) + ")");
    }
  } else {
    bound = bound_of_balls(lat);
    length_scale = glm::length(bound.center) + bound.radius;
    only_naive("the lattice's layout (" + lat.layout().kind() + ") is not a steady brick");
  }
}

void QueryState::only_naive(const std::string& reason) {
  bounds.reset();
  u_nodes.clear();
  u_scales.clear();
  prefix_offsets.clear();
  pattern_prefix.clear();
  slab_prefixes.clear();
  first_templates = {};
  constant_extents.clear();
  plan = {};
  plan.steady_reason = reason;
  plan.slabs_reason = plan.constant_reason = plan.steady_reason;
  plan.automatic = QueryMethod::Naive;
}

void QueryState::prepare_brick_paths() {
  const Lattice& lat = lattice;
  const Counts& c = lat.counts();
  const auto& nodes = lat.definition().nodes;
  const SteadyBrick& brick = *lat.layout().steady_brick();
  auto world = [&](const Similarity& step, std::int64_t count) {
    return PowerTable(brick.placement * step * brick.placement.inverse(), -margin, count - 1 + margin);
  };
  world_u = world(brick.steps[0], c.u);
  world_v = world(brick.steps[1], c.v);
  world_w = world(brick.steps[2], c.w);
  const std::int64_t slots = c.u + 2 * margin;
  if (slots * lat.node_count() <= kMaxPowerTableEntries) {
    for (std::int64_t i = -margin; i < c.u + margin; ++i) {
      const SimilarityTransform t = eval.u().at(i);
      u_scales.push_back(t.scale);
      for (const auto& n : nodes) u_nodes.push_back(t.apply_point(n.center));
    }
  }
  prefix_offsets.emplace_back(0, 0);
  for (const BeamPattern& b : lat.definition().beams) {
    const std::pair<int, int> o(b.dj, b.dk);
    auto it = std::find(prefix_offsets.begin(), prefix_offsets.end(), o);
    if (it == prefix_offsets.end()) it = prefix_offsets.insert(prefix_offsets.end(), o);
    pattern_prefix.push_back(static_cast<int>(it - prefix_offsets.begin()));
  }
  for (const auto& o : prefix_offsets) slab_prefixes.push_back(eval.row_prefix(o.first, o.second));
  first_templates.fill(*this, slab_prefixes, 0);
  detect_plan(*this);
  auto extents = [](const RowMotion& m, const Ball& a, const Ball* b, std::array<Extent, kMaxRowMaps>& out) {
    for (std::size_t x = 0; x < m.maps().size(); ++x) out[x] = b ? m.maps()[x].extent(a, *b) : m.maps()[x].extent(a);
  };
  for (std::size_t n = 0; n < first_templates.nodes.size(); ++n) {
    TemplateExtents e;
    extents(plan.constant_u, first_templates.nodes[n], nullptr, e.u);
    extents(plan.constant_v, first_templates.nodes[n], nullptr, e.v);
    extents(plan.constant_w, first_templates.nodes[n], nullptr, e.w);
    constant_extents.push_back(e);
  }
  for (std::size_t p = 0; p < first_templates.beam_start.size(); ++p) {
    TemplateExtents e;
    const Ball& a = first_templates.beam_start[p];
    const Ball& b = first_templates.beam_end[p];
    extents(plan.constant_u, a, &b, e.u);
    extents(plan.constant_v, a, &b, e.v);
    extents(plan.constant_w, a, &b, e.w);
    constant_extents.push_back(e);
  }
}

Ball bound_of_balls(const Lattice& lat) {
  // Every beam lies in the hull of its end balls, which lie in their nodes' balls: the box of the balls holds
  // the whole lattice.
  const Counts& c = lat.counts();
  Vec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  std::vector<SimilarityTransform> row(static_cast<std::size_t>(c.u));
  for (std::int64_t k = 0; k < c.w; ++k)
    for (std::int64_t j = 0; j < c.v; ++j) {
      lat.layout().row_transforms(j, k, row.data());
      for (const SimilarityTransform& t : row)
        for (const TemplateNode& n : lat.definition().nodes) {
          const Ball b = t.apply(Ball{n.center, n.radius});
          lo = glm::min(lo, b.center - Vec3(b.radius));
          hi = glm::max(hi, b.center + Vec3(b.radius));
        }
    }
  return {0.5 * (lo + hi), 0.5 * glm::length(hi - lo)};
}

namespace {
thread_local std::vector<std::unique_ptr<Scratch>> g_scratch_pool;
thread_local std::size_t g_scratch_depth = 0;
}  // namespace

ScratchLease::ScratchLease() {
  if (g_scratch_depth == g_scratch_pool.size()) g_scratch_pool.push_back(std::make_unique<Scratch>());
  scratch_ = g_scratch_pool[g_scratch_depth++].get();
}

ScratchLease::~ScratchLease() { --g_scratch_depth; }

double QueryState::inflation(const Ball& query) const {
  const Counts& c = lattice.counts();
  const double steps = static_cast<double>(c.u) + static_cast<double>(c.v) + static_cast<double>(c.w);
  return (kQueryInflation + kQueryInflationPerStep * steps) *
         (length_scale + glm::length(query.center) + query.radius);
}

}  // namespace detail

namespace {
// The lattice the query paths run on: the brick lattice when the layout's steps apply in another order (its
// hits are translated back), else the lattice itself.
const Lattice& lattice_for_paths(const Lattice& lattice) {
  const Lattice* brick = lattice.brick_lattice();
  return brick ? *brick : lattice;
}

// Forwards hits found on the brick lattice with the lattice's own indices.
struct FromBrickSink : HitSink {
  const Lattice& lattice;
  HitSink& inner;
  FromBrickSink(const Lattice& l, HitSink& s) : lattice(l), inner(s) {}
  bool on_hit(const ElementHit& hit) override {
    ElementHit h = hit;
    if (h.is_beam) {
      const BeamId id = lattice.from_brick(BeamId{h.i, h.j, h.k, h.kind});
      h.i = id.i, h.j = id.j, h.k = id.k;
      h.index = lattice.beam_index(id);
    } else {
      const NodeId id = lattice.from_brick(NodeId{h.i, h.j, h.k, h.kind});
      h.i = id.i, h.j = id.j, h.k = id.k;
      h.index = lattice.ball_index(id);
    }
    return inner.on_hit(h);
  }
  double reach() const override { return inner.reach(); }
};
}  // namespace

struct LatticeQuery::Impl {
  // A copy (the definition and shared pointers: cheap), so that a query made from a temporary lattice stays
  // valid; the Impl lives on the heap, so the state's reference survives moves of the LatticeQuery.
  const Lattice lattice;
  detail::QueryState state;   // on lattice_for_paths(lattice)
  std::optional<BecotsLatticeQuery> becots;  // on the lattice itself, when it is laid on a BeCOTS map
  explicit Impl(const Lattice& l) : lattice(l), state(lattice_for_paths(lattice)) { detect_becots(); }
  bool translates() const { return &state.lattice != &lattice; }

  void detect_becots() {
    QueryPlan& plan = state.plan;
    if (!plan.steady_reason.empty()) {
      plan.becots_reason = plan.steady_reason;
      return;
    }
    const std::optional<BecotsMap> map = becots_map_of(lattice, &plan.becots_reason);
    if (!map) return;
    try {
      becots.emplace(lattice, *map);
    } catch (const InvalidInput& e) {  // the candidate map does not reproduce the steps, or has no finder
      plan.becots_reason = e.what();
      return;
    }
    plan.becots_valid = true;
    plan.becots_reason.clear();
    plan.automatic = QueryMethod::Becots;
  }
};

namespace {
thread_local std::int64_t g_last_candidates = 0;
}

LatticeQuery::LatticeQuery(const Lattice& lattice) : impl_(std::make_unique<Impl>(lattice)) {}
LatticeQuery::~LatticeQuery() = default;
LatticeQuery::LatticeQuery(LatticeQuery&&) noexcept = default;

const Lattice& LatticeQuery::lattice() const { return impl_->lattice; }
const QueryPlan& LatticeQuery::plan() const { return impl_->state.plan; }
const BlockBounds& LatticeQuery::block_bounds() const {
  if (!impl_->state.bounds) fail_input("block_bounds", impl_->state.plan.steady_reason);
  return *impl_->state.bounds;
}
const Ball& LatticeQuery::bound() const { return impl_->state.bound; }
std::int64_t LatticeQuery::last_candidate_count() { return g_last_candidates; }

QueryMethod LatticeQuery::resolve(QueryMethod method) const {
  const QueryPlan& p = impl_->state.plan;
  if (method != QueryMethod::Auto && method != QueryMethod::Naive && !p.steady_reason.empty())
    fail_input("method", "'" + std::string(to_string(method)) + "' does not apply: " + p.steady_reason +
                             " (use 'naive' or 'auto')");
  switch (method) {
    case QueryMethod::Auto: return p.automatic;
    case QueryMethod::Slabs:
    case QueryMethod::PaperSlabs:
      if (!p.slabs_valid) fail_input("method", std::string("'slabs' (O(u)) does not apply: ") + p.slabs_reason);
      return method;
    case QueryMethod::Constant:
      if (!p.constant_valid)
        fail_input("method", std::string("'constant' (O(1)) does not apply: ") + p.constant_reason);
      return method;
    case QueryMethod::Becots:
      if (!p.becots_valid) fail_input("method", std::string("'becots' does not apply: ") + p.becots_reason);
      return method;
    default: return method;
  }
}

void LatticeQuery::visit(const Ball& query, HitSink& caller_sink, QueryMethod method) const {
  validate_query_ball(query, "query");
  const detail::QueryState& q = impl_->state;
  const QueryMethod m = resolve(method);
  if (m == QueryMethod::Becots) {  // on the lattice's own indices: no brick translation
    g_last_candidates = impl_->becots->visit(query, caller_sink);
    return;
  }
  FromBrickSink translated(impl_->lattice, caller_sink);
  HitSink& sink = impl_->translates() ? static_cast<HitSink&>(translated) : caller_sink;
  detail::Probe probe{q, query, query, sink};
  probe.inflated.radius = query.radius + q.inflation(query);
  if (m == QueryMethod::Slabs || m == QueryMethod::PaperSlabs) probe.inflated.radius += q.plan.slabs_inflation;
  if (m == QueryMethod::Constant) probe.inflated.radius += q.plan.constant_inflation;
  g_last_candidates = 0;
  // Outside the lattice's bound there is nothing to find (the naive path scans regardless: it is the oracle).
  if (m != QueryMethod::Naive && distance_to_ball(query.center, q.bound) > probe.inflated.radius) return;
  switch (m) {
    case QueryMethod::Naive: detail::visit_naive(q, probe); break;
    case QueryMethod::Rows: detail::visit_rows(q, probe, true); break;
    case QueryMethod::PaperRows: detail::visit_rows(q, probe, false); break;
    case QueryMethod::Slabs: detail::visit_slabs(q, probe, true); break;
    case QueryMethod::PaperSlabs: detail::visit_slabs(q, probe, false); break;
    case QueryMethod::Constant: detail::visit_constant(q, probe); break;
    case QueryMethod::Blocks:
    case QueryMethod::Becots:  // handled above
    case QueryMethod::Auto: detail::visit_blocks(q, probe); break;
  }
  g_last_candidates = probe.candidates;
}


BallQueryResult LatticeQuery::query_ball(const Ball& query, QueryMethod method) const {
  validate_query_ball(query, "query");
  const std::int64_t sure = surely_hit(query);
  if (static_cast<std::size_t>(sure) > detail::kUncheckedHits)
    detail::require_result_memory(query, static_cast<std::uint64_t>(sure), "at least");
  return detail::collect_hits(query, [&](HitSink& sink) { visit(query, sink, method); });
}

std::int64_t LatticeQuery::surely_hit(const Ball& query) const {
  validate_query_ball(query, "query");
  return detail::elements_surely_hit(impl_->state, query);
}

bool LatticeQuery::touches(const Ball& query, QueryMethod method) const {
  return detail::any_hit([&](HitSink& sink) { visit(query, sink, method); });
}

}  // namespace steady
