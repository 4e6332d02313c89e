#pragma once
// Ball-interference queries (BIQ) on a steady brick lattice: which balls and beams meet a closed query
// ball. Everything else (point membership, distance, rays, voxels, filters) is built on it.
//
// Paths (QueryMethod):
//   Naive     O(uvw): every element, each ball evaluated once (slab cache), all exact-tested. The oracle.
//   Rows      O(uv), any steady brick: the k-rows (i, j, *) of every ball and beam pattern are steady with
//             W' = G W G^-1 (k-rows of beams too, as both ends move by W'), so RangeFinder gives each
//             row's candidate k in closed form.
//   Slabs     O(u), the paper's special case: when V's normalized maps are unchanged by W and W's by V,
//             the j- and k-ranges of the template at (i, 0, 0) hold for its whole slab (element (i,j,k)
//             is W'^k V'^j of it), and the candidates are their product.
//   Constant  O(1): when U's maps are unchanged by V and W, one i-range from the template at (0,0,0)
//             holds for every row; with V's and W's maps also unchanged by the other two, so do the j-
//             and k-ranges (the paper's O(1)); otherwise j and k come per candidate slab as in Slabs.
//   Blocks    beyond the paper: a hierarchy of index blocks with closed-form bounds (block_bounds.hpp),
//             refined only where the query may be; any steady brick, ~O(log(uvw)) nodes visited.
// Rows and Slabs reject whole rows and slabs before RangeFinder runs (row_invariant.hpp: functions the
// row's motion keeps; for slabs, U's maps that V and W keep), which removes the paper's false positives
// of queries inside a row's slab but far from it. PaperRows and PaperSlabs are the paper's algorithms
// without that rejection, kept to reproduce its tables.
//   Becots    O(1) on a BeCOTS lattice (becots_query.hpp), slab or stack: the map is recovered from the steps
//             (becots_map_of) and its RangeFinder gives the candidate groups of the layers the query's shell of
//             cones meets. The conditions of Slabs and Constant fail on the commuting spirals of these lattices.
//   Auto      Becots when it applies, else Constant when it applies, else Blocks.
// The conditions of Slabs and Constant are detected numerically (kConditionTolerance) when the query
// object is built. Detection is per map, not per direction: a direction keeps only the maps the other
// directions leave unchanged, and extra maps are tried that the paper does not use (the distance to a
// line through a dilation's fixed point; for translations, the dual direction orthogonal to the other
// two), which puts cylindrical and sheared regular lattices in the O(1) class. Unlike the paper, the
// steps need not commute: element (i,j,k) is W'^k V'^j U'^i of the template whatever the order, so
// invariant maps suffice (only a dilation map's beam extents need commuting steps).
//
// Every path tests candidates with the same exact predicates (interference.hpp) on the same element
// geometry as Lattice::ball/beam, so their answers are identical sets.
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "steady/core/ball.hpp"
#include "steady/query/block_bounds.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/query/rangefinder.hpp"

namespace steady {

enum class QueryMethod { Auto, Naive, Rows, Slabs, Constant, Blocks, PaperRows, PaperSlabs, Becots };
const char* to_string(QueryMethod method);
// "auto", "naive", "rows", "slabs", "constant", "blocks", "rows-paper", "slabs-paper", "becots"; throws
// InvalidInput naming `field` otherwise.
QueryMethod query_method_from_string(const std::string& name, const std::string& field = "method");

// An element that meets the query, with its geometry.
struct ElementHit {
  bool is_beam = false;
  int kind = 0;  // node n (balls) or beam pattern p (beams)
  std::int64_t i = 0, j = 0, k = 0;
  std::int64_t index = -1;  // into Lattice::balls() / Lattice::beams()
  Ball ball;                // balls
  BeamGeometry beam;        // beams
  double distance = 0.0;    // signed distance from the query center to the element
};

// Receives the hits of a query; returning false stops the query early.
class HitSink {
 public:
  virtual ~HitSink() = default;
  virtual bool on_hit(const ElementHit& hit) = 0;
  // The distance from the query's center beyond which hits are no longer wanted: a nearest-element search
  // lowers it as it finds nearer elements, and the hierarchical path prunes blocks by it.
  virtual double reach() const { return std::numeric_limits<double>::infinity(); }
};

// What a lattice allows, decided when the query object is built.
struct QueryPlan {
  // Why no path but the naive one applies (the layout is not a steady brick), or empty.
  std::string steady_reason;
  bool slabs_valid = false;
  bool constant_valid = false;
  std::string slabs_reason;     // why Slabs does not apply (empty when it does)
  std::string constant_reason;  // why Constant does not apply
  bool becots_valid = false;
  std::string becots_reason;    // why Becots does not apply
  QueryMethod automatic = QueryMethod::Blocks;
  // The normalized maps each path uses, by direction (world-space steps U', V', W').
  RowMotion rows_w;
  RowMotion slabs_v, slabs_w;
  RowMotion constant_u, constant_v, constant_w;
  // Constant computes the j- and k-ranges per candidate i (from slabs_v, slabs_w) when V's or W's maps
  // change under U (a cylindrical lattice's axial translation under its radial dilation).
  bool constant_per_slab = false;
  // Extra query inflation covering the (tolerated) mismatch of the detected conditions.
  double slabs_inflation = 0.0, constant_inflation = 0.0;
  // The largest measured mismatches (length units) of the conditions, for reports.
  double largest_commutator = 0.0;
  std::string describe() const;
};

struct BallQueryResult {
  std::vector<std::int64_t> balls, beams;  // sorted indices into Lattice::balls() / beams()
};

class LatticeQuery {
 public:
  // O(u + v + w): power tables and the condition checks. The query keeps its own copy of `lattice`.
  explicit LatticeQuery(const Lattice& lattice);
  ~LatticeQuery();
  LatticeQuery(LatticeQuery&&) noexcept;

  const Lattice& lattice() const;
  const QueryPlan& plan() const;
  const BlockBounds& block_bounds() const;
  // A ball containing the whole lattice.
  const Ball& bound() const;
  // The method Auto resolves to, or `method` itself after checking it applies (InvalidInput otherwise).
  QueryMethod resolve(QueryMethod method) const;

  // Calls sink.on_hit for every element meeting the closed ball `query` (touching counts), in no
  // particular order, until it returns false. Throws InvalidInput for a NaN or negative radius.
  void visit(const Ball& query, HitSink& sink, QueryMethod method = QueryMethod::Auto) const;

  // Refuses (ResourceLimit, naming the radius) a result that surely exceeds the memory budget before visiting
  // anything, and one that grows beyond it while collected.
  BallQueryResult query_ball(const Ball& query, QueryMethod method = QueryMethod::Auto) const;
  // A lower bound of the number of elements query_ball(query) returns, without visiting any (its memory check).
  std::int64_t surely_hit(const Ball& query) const;
  // True when some element meets the ball (stops at the first hit).
  bool touches(const Ball& query, QueryMethod method = QueryMethod::Auto) const;

  // Number of candidate elements the last call of visit on this thread tested exactly (for benchmarks).
  static std::int64_t last_candidate_count();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A query ball reaches at most this far (model units): it holds any lattice of the supported range
// (numeric_range.hpp) seen from any point of it.
constexpr double kMaxQueryRadius = 4e12;

// Throws InvalidInput naming `field` unless the ball's center is within the supported range and its radius
// is in [0, kMaxQueryRadius].
void validate_query_ball(const Ball& query, const std::string& field);

}  // namespace steady
